#include "platform/tools/export_sequence.h"

#include <fmt/format.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "models/fhg/sequence_cache.h"
#include "models/fhg/rtl_parameters.h"
#include "models/fhg/sequence_memory.h"
#include "platform/cost/fpga_resources.h"
#include "platform/report/json_input.h"
#include "platform/run/output_folder.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/config.h"
#include "platform/scenario/scenario.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

constexpr std::uintmax_t kMaxImageBytes = 64u << 20;  // a 512-deep image of 1,000-bit words is 130 KiB

std::string machine(const fhg::SequenceParams& p) {
    return fmt::format("{} scheduler, {} {} read buses, {} TripleMACs, line FIFO {}, reuse {}",
                       fhg::scheduler_name(p.scheduler), p.read_buses, fhg::bus_word_name(p.bus_word), p.triple_macs,
                       fhg::line_fifo_name(p.line_fifo), p.reuse ? "on" : "off");
}

Json summary(const fhg::SequenceImage& image, const fhg::Sequence& s, const fhg::SequenceParams& p) {
    Json fields = Json::array();
    for (const fhg::MemoryField& f : image.layout.fields)
        fields.push_back({{"name", f.name}, {"lsb", f.lsb}, {"width", f.width}, {"meaning", f.meaning}});
    return {{"machine", machine(p)},
            {"depth", image.words.size()},
            {"width_bits", image.layout.width},
            {"ramb36", ramb36_for(image.words.size(), unsigned(image.layout.width))},
            {"interval_cycles", s.interval},
            {"words_delivered", s.words_delivered},
            {"files", {"fhg_sequence.coe", "fhg_sequence.mem", "fhg_params.vh"}},
            {"fields", fields}};
}

// Decodes the image under the configuration's layout and replays it: the first broken limit
// (or undecodable word) is bad input, named with the file.
int check_image(const ExportSequenceOptions& o, const fhg::SequenceParams& p) {
    const std::string text = read_input_file(o.check, "a sequence image", kMaxImageBytes);
    fhg::Sequence s;
    try {
        s = fhg::decode_sequence(fhg::parse_image(text, fhg::sequence_layout(p)), p);
    } catch (const std::invalid_argument& e) {
        throw ConfigError(fmt::format("--check {}: {}", o.check, e.what()));
    }
    const std::string broken = fhg::check_sequence(s, p);
    if (!broken.empty()) throw ConfigError(fmt::format("--check {}: the replay fails: {}", o.check, broken));
    std::printf("%s: %d words, %zu bus words; the replay checker accepts it for the %s\n", o.check.c_str(), s.interval,
                s.steps.size(), machine(p).c_str());
    return 0;
}

}  // namespace

int export_sequence_command(const ExportSequenceOptions& o) {
    const Fhg::Params chip = fhg_params(scenario_or_defaults(o.scenario, o.sets));
    const fhg::SequenceParams& p = chip.sequence;
    if (!o.check.empty()) return check_image(o, p);
    const fhg::Sequence* s = nullptr;
    std::string rtl;
    try {
        s = &fhg::cached_sequence(p);
        rtl = fhg::rtl_parameters(chip.precision, p, chip.max_width);
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
    const fhg::SequenceImage image = fhg::encode_sequence(*s, p);
    const std::string title = "surfvp FHG sequence memory: " + machine(p);
    const Json j = summary(image, *s, p);
    OutputFolder folder(o.out, {"fhg_sequence.coe", "fhg_sequence.mem", "fhg_sequence.json", "fhg_params.vh"});
    folder.publish_files({{"fhg_sequence.coe", fhg::to_coe(image, title)},
                          {"fhg_sequence.mem", fhg::to_readmemh(image, title)},
                          {"fhg_sequence.json", j.dump(2) + "\n"},
                          {"fhg_params.vh", rtl}});
    std::printf("%s\n%zu words x %d bits in %u RAMB36: %s/fhg_sequence.{coe,mem,json}, fhg_params.vh\n", title.c_str(),
                image.words.size(), image.layout.width, j["ramb36"].get<unsigned>(), o.out.c_str());
    return 0;
}

}  // namespace surfvp
