#pragma once
// Breaks a sequence memory image in the one way only the line FIFO's wiring notices: two buses
// trade places in a word. Every TripleMAC still takes the same value, but the buses' lanes are
// wired to other BRAM ports (lane_port), so two of them may now ask one port for two addresses.
#include <stdexcept>
#include <string>
#include <utility>

#include "models/fhg/sequence_memory.h"

namespace surfvp::fhg {

// Swaps buses a and b in word i: their fields, and the bus field of the TripleMACs taking from them.
inline void swap_buses(SequenceImage& image, size_t i, int a, int b) {
    const MemoryLayout& l = image.layout;
    MemoryWord& word = image.words[i];
    const std::string first = "bus" + std::to_string(a) + "_", second = "bus" + std::to_string(b) + "_";
    for (const MemoryField& f : l.fields) {
        if (f.name.rfind(first, 0) != 0) continue;
        const MemoryField& other = l.field(second + f.name.substr(first.size()));
        const uint64_t v = field_value(word, f);
        set_field(word, f, field_value(word, other));
        set_field(word, other, v);
    }
    for (const MemoryField& bus : l.fields) {
        if (bus.name.rfind("mac", 0) != 0 || bus.name.size() < 4 || bus.name.substr(bus.name.size() - 4) != "_bus")
            continue;
        const std::string take = bus.name.substr(0, bus.name.size() - 4) + "_take";
        const uint64_t from = field_value(word, bus);
        if (field_value(word, l.field(take)) && (from == uint64_t(a) || from == uint64_t(b)))
            set_field(word, bus, from == uint64_t(a) ? uint64_t(b) : uint64_t(a));
    }
}

// The first word in which swapping buses a and b asks a port for two addresses (the decoder
// refuses it), or the image's size if there is none.
inline size_t word_a_swap_breaks(const SequenceImage& image, const SequenceParams& p, int a, int b) {
    for (size_t i = 0; i < image.words.size(); ++i) {
        SequenceImage swapped = image;
        swap_buses(swapped, i, a, b);
        try {
            decode_sequence(swapped, p);
        } catch (const std::invalid_argument&) {
            return i;
        }
    }
    return image.words.size();
}

}  // namespace surfvp::fhg
