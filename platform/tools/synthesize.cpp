#include "platform/tools/synthesize.h"

#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "models/fhg/rtl_parameters.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/sequence_memory.h"
#include "models/host/atomic_file.h"
#include "models/host/shell.h"
#include "platform/cost/fpga_resources.h"
#include "platform/run/output_folder.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/config.h"
#include "platform/scenario/scenario.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The families synth_xilinx maps, and the device names that belong to each.
constexpr std::array<std::pair<const char*, const char*>, 4> kFamilies{
    {{"xc5v", "XC5V"}, {"xc6s", "XC6S"}, {"xc6v", "XC6V"}, {"xc7", "XC7"}}};

std::string family_of(const SynthesizeOptions& o, const Config& c) {
    if (!o.family.empty()) {
        for (const auto& [family, prefix] : kFamilies)
            if (o.family == family) return family;
        throw ConfigError(
            fmt::format("--family {}: not a family synth_xilinx maps here: xc5v, xc6s, xc6v or xc7", o.family));
    }
    const std::string device = c.choice("fpga.device");
    for (const auto& [family, prefix] : kFamilies)
        if (device.rfind(prefix, 0) == 0) return family;
    throw ConfigError(fmt::format("{}: {} names no FPGA family: give one with --family (xc5v, xc6s, xc6v, xc7)",
                                  c.where("fpga.device"), device));
}

// The log's last line that says ERROR (the folder with the log is not published).
std::string last_error(const fs::path& log) {
    std::ifstream in(log);
    std::string found = "no log", line;
    while (std::getline(in, line))
        if (line.find("ERROR") != std::string::npos) found = line;
    return found;
}

// A part of the FHG as yosys synthesizes it alone: its top module and files, and the model's
// estimate of one of it.
struct Part {
    std::string name, top;
    std::vector<std::string> files;
    std::string prepare;  // yosys commands between reading and synthesizing
    BlockResources model;
    unsigned count = 1;  // how many the FHG has
};

// One block RAM of the line FIFO (line_ram.v) in the organisation fhg.line_fifo names: a line,
// or a column bank of one, with its read ports; the model's share of the FIFO's RAMB36 each.
Part line_fifo_ram(const Fhg::Params& chip, const BlockResources& line_fifo) {
    const fhg::LineFifoShape shape = fhg::line_fifo_shape(chip.sequence.line_fifo);
    const fhg::LineBram bram = fhg::line_bram(chip.sequence.line_fifo, chip.max_width);
    const unsigned count = chip.sequence.fifo_lines * unsigned(shape.banks);
    BlockResources one = line_fifo;
    one.ramb36 /= count;
    one.luts /= count;
    one.ffs /= count;
    return {"line FIFO BRAM",
            "line_ram",
            {"line_ram.v"},
            fmt::format("chparam -set WORDS {} -set ADDR_BITS {} -set PAIRS {} -set READS {} line_ram; ", bram.words,
                        bram.address_bits, shape.aligned_pairs ? 1 : 0, shape.reads),
            one,
            count};
}

// The whole line FIFO (line_fifo.v): its BRAMs and the routing between them and the bus lanes,
// which no part alone has. The model's figure is the two parts together.
Part whole_line_fifo(const FhgParts& model) {
    BlockResources both = model.line_fifo;
    both.luts += model.line_routing.luts;
    both.ffs += model.line_routing.ffs;
    both.basis += "; " + model.line_routing.basis;
    return {"line FIFO, whole", "line_fifo", {"line_fifo.v", "line_ram.v"}, "", both, 1};
}

// Cells by kind: LUTs (INV is a LUT1), flip-flops, DSP slices, RAMB36 (a RAMB18 or RAMB16 is
// half one, a RAMB8 a quarter).
Json resources_of(const Json& stat) {
    double luts = 0, ffs = 0, dsp = 0, ramb36 = 0;
    Json other = Json::object();
    for (const auto& [cell, n] : stat.at("design").at("num_cells_by_type").items()) {
        const double count = n.get<double>();
        if (cell.rfind("LUT", 0) == 0 || cell == "INV")
            luts += count;
        else if (cell.rfind("FD", 0) == 0)
            ffs += count;
        else if (cell.rfind("DSP48", 0) == 0)
            dsp += count;
        else if (cell.rfind("RAMB36", 0) == 0)
            ramb36 += count;
        else if (cell.rfind("RAMB18", 0) == 0 || cell.rfind("RAMB16", 0) == 0)  // Spartan-6's RAMB16BWER: 18 Kbit
            ramb36 += count / 2;
        else if (cell.rfind("RAMB8", 0) == 0)
            ramb36 += count / 4;
        else
            other[cell] = n;
    }
    return {{"luts", luts}, {"ffs", ffs}, {"dsp48e", dsp}, {"ramb36", ramb36}, {"other_cells", other}};
}

Json synthesize(const Part& part, const fs::path& rtl, const fs::path& logs, const std::string& family) {
    const fs::path log = logs / (part.top + ".log"), stat = logs / (part.top + ".json");
    std::string files;
    for (const std::string& f : part.files) files += " " + f;
    const std::string script = fmt::format(
        "read_verilog -I.{}; {}synth_xilinx -flatten -noiopad -family {} -top {}; tee -q -o ../yosys/{}.json stat "
        "-json",
        files, part.prepare, family, part.top, part.top);  // relative: yosys's commands take no quoted paths
    const std::string command = fmt::format("cd {} && yosys -q -l {} -p {} >/dev/null 2>&1", shell_quoted(rtl.string()),
                                            shell_quoted(log.string()), shell_quoted(script));
    if (std::system(command.c_str()) != 0 || !fs::exists(stat))
        throw std::runtime_error(
            fmt::format("yosys could not synthesize {} for {}: {}", part.top, family, last_error(log)));
    std::ifstream in(stat);
    return resources_of(Json::parse(in));
}

Json model_json(const BlockResources& b) {
    return {{"luts", b.luts}, {"ffs", b.ffs}, {"dsp48e", b.dsp48e}, {"ramb36", b.ramb36}, {"basis", b.basis}};
}

std::string ratio(double synthesized, double model) {
    if (model == 0) return synthesized == 0 ? "=" : "-";
    return fmt::format("{:.2f}", synthesized / model);
}

std::string markdown(const Json& j) {
    std::string s = fmt::format(
        "# The FHG datapath synthesized\n\n{} synthesized the Verilog reference (models/fhg/rtl) with this "
        "configuration's parameters for {} (`synth_xilinx -family {} -flatten -noiopad`, each part alone) beside "
        "the resource model's estimate (docs/resources.md). Each figure is for one of the part; the FHG has "
        "`count` of it.\n\n"
        "| part | count | LUTs (yosys / model) | flip-flops | DSP48E | RAMB36 | LUT ratio | FF ratio |\n"
        "|---|---:|---|---|---|---|---:|---:|\n",
        j["yosys"].get<std::string>(), j["device"].get<std::string>(), j["family"].get<std::string>());
    for (const Json& p : j["parts"]) {
        const Json &y = p["yosys"], &m = p["model"];
        auto pair = [&](const char* k) { return fmt::format("{:g} / {:g}", y[k].get<double>(), m[k].get<double>()); };
        s += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |\n", p["part"].get<std::string>(),
                         p["count"].get<unsigned>(), pair("luts"), pair("ffs"), pair("dsp48e"), pair("ramb36"),
                         ratio(y["luts"].get<double>(), m["luts"].get<double>()),
                         ratio(y["ffs"].get<double>(), m["ffs"].get<double>()));
    }
    s += "\nNot synthesized here (the model's estimates stand alone):\n\n";
    for (const Json& n : j["not_synthesized"]) s += "- " + n.get<std::string>() + "\n";
    return s;
}

}  // namespace

int synthesize_command(const SynthesizeOptions& o) {
    const Config c = scenario_or_defaults(o.scenario, o.sets);
    const std::string family = family_of(o, c);
    const std::string version = first_output_line("yosys -V 2>/dev/null");
    if (version.empty())
        throw ConfigError("yosys is not installed (scripts/packages.sh test installs it; Debian package yosys)");
    const Fhg::Params chip = fhg_params(c);
    std::string parameters;
    fhg::SequenceImage image;
    try {
        parameters = fhg::rtl_parameters(chip.precision, chip.sequence, chip.max_width);
        image = fhg::encode_sequence(fhg::cached_sequence(chip.sequence), chip.sequence);
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
    if (image.words.size() > fhg::kRtlSequenceDepth)
        throw ConfigError(fmt::format("the sequence is {} words long; the RTL's sequence memory holds {}",
                                      image.words.size(), fhg::kRtlSequenceDepth));
    const FhgParts model = fhg_parts(c);
    std::vector<Part> parts{
        {"TripleMAC",
         "triple_mac",
         {"triple_mac.v"},
         fmt::format("chparam -set ACC_BITS {} -set X3_CYCLES {} triple_mac; ", chip.precision.accumulator_bits,
                     chip.sequence.x3_cycles),
         model.triple_mac,
         chip.sequence.triple_macs},
        {"HessianCalc", "hessian_calc", {"hessian_calc.v", "round_saturate.v"}, "", model.hessian_calc, 1},
        {"sequence memory", "sequence_memory", {"sequence_memory.v"}, "", model.sequence_memory, 1},
        line_fifo_ram(chip, model.line_fifo)};
    if (o.whole_fifo) parts.push_back(whole_line_fifo(model));

    OutputFolder folder(o.out, {"rtl", "yosys", "synthesis.md", "synthesis.json"});
    // Absolute: yosys runs in rtl/ and writes its log and statistics beside it.
    const fs::path staging = fs::absolute(folder.staging()), rtl = staging / "rtl", logs = staging / "yosys";
    fs::create_directories(rtl);
    fs::create_directories(logs);
    for (const auto& entry : fs::directory_iterator(SURFVP_RTL_SOURCE_DIR))
        if (entry.path().extension() == ".v") fs::copy_file(entry.path(), rtl / entry.path().filename());
    write_file_atomically(rtl / "fhg_params.vh", parameters);
    write_file_atomically(rtl / "fhg_sequence.mem", fhg::to_readmemh(image, "surfvp synthesize"));

    Json j{{"yosys", version}, {"family", family}, {"device", c.choice("fpga.device")}, {"parts", Json::array()}};
    for (const Part& p : parts) {
        const Json y = synthesize(p, rtl, logs, family);
        j["parts"].push_back(
            {{"part", p.name}, {"top", p.top}, {"count", p.count}, {"yosys", y}, {"model", model_json(p.model)}});
    }
    j["not_synthesized"] = Json::array();
    if (!o.whole_fifo)
        j["not_synthesized"].push_back(fmt::format(
            "the line FIFO's routing of the bus lanes to its BRAMs' ports ({:.0f} LUTs and {:.0f} flip-flops by the "
            "model): --whole-fifo synthesizes the whole FIFO, which takes minutes (docs/rtl.md)",
            model.line_routing.luts, model.line_routing.ffs));
    j["not_synthesized"].push_back(
        "LocMaxFinder, the maxima FIFO, the determinant row buffers and the control: not in the RTL");
    write_file_atomically(staging / "synthesis.json", j.dump(2) + "\n");
    const std::string md = markdown(j);
    write_file_atomically(staging / "synthesis.md", md);
    folder.publish();
    std::printf("%s\nsynthesis in %s/synthesis.{md,json}; the Verilog in %s/rtl\n", md.c_str(), o.out.c_str(),
                o.out.c_str());
    return 0;
}

}  // namespace surfvp
