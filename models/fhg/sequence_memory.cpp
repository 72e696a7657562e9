#include "sequence_memory.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>
#include <stdexcept>

#include "filter_geometry.h"

namespace surfvp::fhg {
namespace {

// Bits to number n things; a field is at least one bit wide so the RTL can always slice it.
int bits_for(unsigned n) {
    int b = 1;
    while ((1u << b) < n) ++b;
    return b;
}

int lanes(BusWord word) { return int(word_shape(word).size()); }

// Coefficients as two bits: bit 0 the sign, bit 1 the x3 (three additions).
constexpr int kCoefficients[4] = {+1, -1, +3, -3};
int coefficient_code(int coefficient) {
    for (int c = 0; c < 4; ++c)
        if (kCoefficients[c] == coefficient) return c;
    throw std::invalid_argument("a tap with coefficient " + std::to_string(coefficient));
}

std::string bus_name(int b) { return "bus" + std::to_string(b); }
std::string mac_name(int t) { return "mac" + std::to_string(t); }
std::string lane_name(int b, int l) { return bus_name(b) + "_lane" + std::to_string(l); }

// The lanes of a bus word that its TripleMACs take: the values the line FIFO reads.
std::vector<int> read_lanes(const Step& step) {
    std::vector<int> lanes;
    for (const Tap& tap : step.taps) lanes.push_back(tap.lane);
    std::sort(lanes.begin(), lanes.end());
    lanes.erase(std::unique(lanes.begin(), lanes.end()), lanes.end());
    return lanes;
}

std::string at_word(size_t i) { return "sequence memory word " + std::to_string(i); }

int hex_digits(const MemoryLayout& layout) { return (layout.width + 3) / 4; }

std::string hex(const MemoryWord& word, int digits) {
    static const char kHex[] = "0123456789abcdef";
    std::string s;
    for (int d = digits - 1; d >= 0; --d) s += kHex[(word[size_t(d / 16)] >> (4 * (d % 16))) & 15];
    return s;
}

MemoryWord parse_word(const std::string& token, const MemoryLayout& layout, int line) {
    const std::string where = "line " + std::to_string(line) + ": '" + token + "'";
    const int digits = hex_digits(layout);
    // Exactly the digits the writer gives: a word of another machine's layout is named as such.
    if (int(token.size()) != digits)
        throw std::invalid_argument(where + " is not a word of " + std::to_string(layout.width) + " bits (" +
                                    std::to_string(digits) + " hex digits; it has " + std::to_string(token.size()) +
                                    ")");
    MemoryWord word(size_t((layout.width + 63) / 64), 0);
    for (size_t i = 0; i < token.size(); ++i) {
        const char c = char(std::tolower(static_cast<unsigned char>(token[token.size() - 1 - i])));
        const int v = std::isdigit(static_cast<unsigned char>(c)) ? c - '0'
                      : (c >= 'a' && c <= 'f')                    ? c - 'a' + 10
                                                                  : -1;
        if (v < 0) throw std::invalid_argument(where + " is not hexadecimal");
        if (int(4 * i) + 4 > layout.width && (v >> std::max(0, layout.width - int(4 * i))) != 0)
            throw std::invalid_argument(where + " has bits above the word's " + std::to_string(layout.width));
        word[i / 16] |= uint64_t(v) << (4 * (i % 16));
    }
    return word;
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// One `last` bit, then each bus's fields, then each TripleMAC's.
void add(MemoryLayout& layout, std::string name, int width, std::string meaning) {
    layout.fields.push_back({std::move(name), layout.width, width, std::move(meaning)});
    layout.width += width;
}

// Word i's read bits must be what the encoder writes: exactly the lanes its TripleMACs take. Each
// lane reads through the port it is wired to (lane_port), which reads one address a cycle.
void check_reads(const MemoryWord& word, const MemoryLayout& l, const SequenceParams& p, const std::vector<Step>& steps,
                 size_t first, size_t i) {
    std::map<std::pair<int, int>, std::pair<int, std::string>> unit_on;  // (BRAM, port): its unit, and who reads it
    for (int b = 0; b < int(p.read_buses); ++b) {
        const auto step =
            std::find_if(steps.begin() + long(first), steps.end(), [&](const Step& s) { return s.bus == b; });
        const std::vector<int> taken = step == steps.end() ? std::vector<int>{} : read_lanes(*step);
        for (int lane = 0; lane < lanes(p.bus_word); ++lane) {
            const std::string name = lane_name(b, lane);
            const uint64_t read = field_value(word, l.field(name + "_read"));
            const bool wanted = std::count(taken.begin(), taken.end(), lane) > 0;
            if (read != uint64_t(wanted))
                throw std::invalid_argument(at_word(i) + ": " + name + "_read is " + std::to_string(read) + ", but " +
                                            (wanted ? "a TripleMAC takes the value" : "no TripleMAC takes it"));
            if (!read) continue;
            const auto& d = word_shape(p.bus_word)[size_t(lane)];
            const LineRead r = line_read(p, step->y + d[0], step->x + d[1]);
            const int port = lane_port(p, b, lane);
            const auto [on, fresh] = unit_on.emplace(std::make_pair(r.bram, port), std::make_pair(r.unit, name));
            if (!fresh && on->second.first != r.unit)
                throw std::invalid_argument(at_word(i) + ": " + name + " and " + on->second.second +
                                            " read two addresses of one BRAM through port " + std::to_string(port) +
                                            ", the port both are wired to");
        }
    }
}

}  // namespace

const MemoryField& MemoryLayout::field(const std::string& name) const {
    for (const MemoryField& f : fields)
        if (f.name == name) return f;
    throw std::invalid_argument("the sequence memory has no field " + name);
}

MemoryLayout sequence_layout(const SequenceParams& params) {
    MemoryLayout layout;
    const int coordinate = bits_for(unsigned(kWindow));
    add(layout, "last", 1, "the interval's final word: the sequence starts again next cycle, results latch");
    for (int b = 0; b < int(params.read_buses); ++b) {
        add(layout, bus_name(b) + "_valid", 1, "the bus carries a word this cycle");
        add(layout, bus_name(b) + "_line", coordinate, "the word's line in the window: y + 26 (0..51)");
        add(layout, bus_name(b) + "_column", coordinate, "the word's column in the window: x + 26 (0..51)");
        for (int l = 0; l < lanes(params.bus_word); ++l) {
            const std::string lane = lane_name(b, l);
            add(layout, lane + "_read", 1, "the line FIFO reads this value of the word (a TripleMAC takes it)");
        }
    }
    for (int t = 0; t < int(params.triple_macs); ++t) {
        add(layout, mac_name(t) + "_take", 1, "the TripleMAC adds a value this cycle");
        add(layout, mac_name(t) + "_bus", bits_for(params.read_buses), "from this bus");
        add(layout, mac_name(t) + "_lane", bits_for(unsigned(lanes(params.bus_word))),
            "this value of the bus word (quad: 2 dy + dx; pair: dx)");
        add(layout, mac_name(t) + "_coefficient", 2, "0: +1, 1: -1, 2: +3, 3: -3 (x3: three additions, busy)");
        add(layout, mac_name(t) + "_response", 2, "0: Dxx, 1: Dyy, 2: Dxy");
    }
    return layout;
}

uint64_t field_value(const MemoryWord& word, const MemoryField& field) {
    uint64_t v = 0;
    for (int i = 0; i < field.width; ++i) {
        const int bit = field.lsb + i;
        v |= ((word[size_t(bit / 64)] >> (bit % 64)) & 1u) << i;
    }
    return v;
}

void set_field(MemoryWord& word, const MemoryField& field, uint64_t value) {
    for (int i = 0; i < field.width; ++i) {
        const int bit = field.lsb + i;
        const uint64_t mask = uint64_t(1) << (bit % 64);
        word[size_t(bit / 64)] = ((value >> i) & 1u) ? word[size_t(bit / 64)] | mask : word[size_t(bit / 64)] & ~mask;
    }
}

SequenceImage encode_sequence(const Sequence& sequence, const SequenceParams& params) {
    SequenceImage image{sequence_layout(params), {}};
    const MemoryLayout& l = image.layout;
    if (sequence.interval <= 0) throw std::invalid_argument("a sequence without an interval has no memory image");
    image.words.assign(size_t(sequence.interval), MemoryWord(size_t((l.width + 63) / 64), 0));
    set_field(image.words.back(), l.field("last"), 1);
    for (const Step& step : sequence.steps) {
        if (step.cycle < 0 || step.cycle >= sequence.interval || step.bus < 0 || step.bus >= int(params.read_buses))
            throw std::invalid_argument("a step outside the interval or the buses");
        MemoryWord& word = image.words[size_t(step.cycle)];
        const std::string bus = bus_name(step.bus);
        set_field(word, l.field(bus + "_valid"), 1);
        set_field(word, l.field(bus + "_line"), uint64_t(step.y + kReachBefore));
        set_field(word, l.field(bus + "_column"), uint64_t(step.x + kReachBefore));
        for (const Tap& tap : step.taps) {
            const std::string mac = mac_name(tap.triple_mac);
            set_field(word, l.field(mac + "_take"), 1);
            set_field(word, l.field(mac + "_bus"), uint64_t(step.bus));
            set_field(word, l.field(mac + "_lane"), uint64_t(tap.lane));
            set_field(word, l.field(mac + "_coefficient"), uint64_t(coefficient_code(tap.coefficient)));
            set_field(word, l.field(mac + "_response"), uint64_t(tap.response));
        }
        for (int lane : read_lanes(step)) set_field(word, l.field(lane_name(step.bus, lane) + "_read"), 1);
    }
    return image;
}

Sequence decode_sequence(const SequenceImage& image, const SequenceParams& params) {
    const MemoryLayout& l = image.layout;
    if (image.words.empty()) throw std::invalid_argument("the sequence memory is empty");
    Sequence sequence;
    sequence.interval = int(image.words.size());
    for (size_t i = 0; i < image.words.size(); ++i) {
        const MemoryWord& word = image.words[i];
        auto get = [&](const std::string& name) { return field_value(word, l.field(name)); };
        const bool final = i + 1 == image.words.size();
        if (get("last") != uint64_t(final))
            throw std::invalid_argument(at_word(i) + ": last is " + std::to_string(get("last")) +
                                        (final ? ", but the image ends here" : ", but words follow"));
        const size_t first_step = sequence.steps.size();
        for (int b = 0; b < int(params.read_buses); ++b) {
            const std::string bus = bus_name(b);
            const uint64_t line = get(bus + "_line"), column = get(bus + "_column");
            if (!get(bus + "_valid")) {
                if (line || column)
                    throw std::invalid_argument(at_word(i) + ": " + bus + " is idle but has an address");
                continue;
            }
            if (line >= uint64_t(kWindow) || column >= uint64_t(kWindow))
                throw std::invalid_argument(at_word(i) + ": " + bus + "_line " + std::to_string(line) + ", " + bus +
                                            "_column " + std::to_string(column) + " is outside the 52 x 52 window");
            sequence.steps.push_back({int(i), b, int(column) - kReachBefore, int(line) - kReachBefore, {}});
        }
        for (int t = 0; t < int(params.triple_macs); ++t) {
            const std::string mac = mac_name(t);
            const uint64_t bus = get(mac + "_bus"), lane = get(mac + "_lane"), code = get(mac + "_coefficient"),
                           response = get(mac + "_response");
            if (!get(mac + "_take")) {
                if (bus || lane || code || response)
                    throw std::invalid_argument(at_word(i) + ": " + mac + " takes nothing but has fields set");
                continue;
            }
            const auto step = std::find_if(sequence.steps.begin() + long(first_step), sequence.steps.end(),
                                           [&](const Step& s) { return uint64_t(s.bus) == bus; });
            if (step == sequence.steps.end())
                throw std::invalid_argument(at_word(i) + ": " + mac + " takes from bus " + std::to_string(bus) +
                                            ", which carries no word");
            if (lane >= uint64_t(lanes(params.bus_word)) || response > 2)
                throw std::invalid_argument(at_word(i) + ": " + mac + " has lane " + std::to_string(lane) +
                                            " and response " + std::to_string(response) + ", which do not exist");
            step->taps.push_back({t, int(lane), kCoefficients[code], Response(response)});
        }
        check_reads(word, l, params, sequence.steps, first_step, i);
    }
    return sequence;
}

std::string to_coe(const SequenceImage& image, const std::string& title) {
    std::ostringstream out;
    out << "; " << title << "\n; " << image.words.size() << " words of " << image.layout.width
        << " bits, layout in docs/sequence-memory.md\nmemory_initialization_radix=16;\nmemory_initialization_vector=\n";
    for (size_t i = 0; i < image.words.size(); ++i)
        out << hex(image.words[i], hex_digits(image.layout)) << (i + 1 == image.words.size() ? ";\n" : ",\n");
    return out.str();
}

std::string to_readmemh(const SequenceImage& image, const std::string& title) {
    std::ostringstream out;
    out << "// " << title << "\n// " << image.words.size() << " words of " << image.layout.width
        << " bits, layout in docs/sequence-memory.md\n";
    for (const MemoryWord& word : image.words) out << hex(word, hex_digits(image.layout)) << "\n";
    return out.str();
}

SequenceImage parse_image(const std::string& text, const MemoryLayout& layout) {
    SequenceImage image{layout, {}};
    const bool coe = text.find("memory_initialization_radix") != std::string::npos;
    bool in_vector = !coe, ended = false;
    std::istringstream lines(text);
    std::string raw;
    for (int n = 1; std::getline(lines, raw); ++n) {
        std::string line = trim(coe ? raw : raw.substr(0, raw.find("//")));
        if (line.empty() || (coe && line[0] == ';')) continue;
        const std::string where = "line " + std::to_string(n);
        if (ended) throw std::invalid_argument(where + ": text after the vector's closing ';'");
        if (coe && !in_vector) {
            std::string compact;
            for (char c : line)
                if (!std::isspace(static_cast<unsigned char>(c))) compact += c;
            if (compact.rfind("memory_initialization_radix=", 0) == 0) {
                if (compact != "memory_initialization_radix=16;")
                    throw std::invalid_argument(where + ": only radix 16 is read (" + line + ")");
                continue;
            }
            if (compact.rfind("memory_initialization_vector=", 0) != 0)
                throw std::invalid_argument(where + ": not a COE statement: " + line);
            in_vector = true;
            line = trim(line.substr(line.find('=') + 1));
        }
        if (!coe && line[0] == '@')
            throw std::invalid_argument(where + ": addresses (@) are not read: one word a line");
        for (char& c : line)
            if (c == ',') c = ' ';
        std::istringstream tokens(line);
        for (std::string token; tokens >> token;) {
            if (coe && token.back() == ';') token.pop_back(), ended = true;
            if (!token.empty()) image.words.push_back(parse_word(token, layout, n));
        }
    }
    if (coe && !ended) throw std::invalid_argument("the COE vector does not end with ';'");
    if (image.words.empty()) throw std::invalid_argument("no words");
    return image;
}

}  // namespace surfvp::fhg
