#include "report.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>

namespace surfvp {
namespace {

std::string ms(double seconds) { return fmt::format("{:.3f} ms", seconds * 1e3); }
std::string percent(double share) { return fmt::format("{:.1f} %", share * 100); }

void bus_section(std::string& md, const std::string& name, const nlohmann::ordered_json& bus) {
    md += fmt::format("\n### {} ({} bit at {} MHz)\n\n", name, bus["width_bits"].get<unsigned>(),
                      bus["clock_hz"].get<double>() / 1e6);
    md += "| path | transactions | bytes | busy | utilisation |\n|---|---:|---:|---:|---:|\n";
    for (const char* path : {"read", "write"}) {
        const auto& p = bus[path];
        md += fmt::format("| {} | {} | {} | {} | {} |\n", path, p["transactions"].get<uint64_t>(),
                          p["bytes"].get<uint64_t>(), ms(p["busy_s"]), percent(p["utilisation"]));
    }
    md += "\n| master | transactions | bytes read | bytes written | busy | waited | errors |\n"
          "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& [master, m] : bus["masters"].items())
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", master, m["transactions"].get<uint64_t>(),
                          m["bytes_read"].get<uint64_t>(), m["bytes_written"].get<uint64_t>(), ms(m["busy_s"]),
                          ms(m["wait_s"]), m["errors"].get<uint64_t>());
}

}  // namespace

std::string report_markdown(const nlohmann::ordered_json& r) {
    std::string md = fmt::format("# surfvp run: {}\n\n{}\n\n", r["scenario"]["name"].get<std::string>(),
                                 r["scenario"]["description"].get<std::string>());
    md += fmt::format("**Result: {}**", r["passed"].get<bool>() ? "passed" : "FAILED");
    if (r.contains("failure")) md += fmt::format(": {}", r["failure"].get<std::string>());
    md += "\n\n| check | result | detail |\n|---|---|---|\n";
    for (const auto& c : r["checks"])
        md += fmt::format("| {} | {} | {} |\n", c["name"].get<std::string>(), c["passed"].get<bool>() ? "pass" : "FAIL",
                          c["detail"].get<std::string>());
    md += "\n## Time\n\n| | |\n|---|---:|\n";
    md += fmt::format("| simulated time | {} |\n", ms(r["sim_time_s"]));
    md += fmt::format("| wall time | {} |\n", ms(r["wall_time_s"]));
    md += fmt::format("| real-time factor (simulated / wall) | {:.4g} |\n", r["real_time_factor"].get<double>());
    md += fmt::format("| bus transactions | {} ({:.3g} per wall second) |\n", r["transactions"].get<uint64_t>(),
                      r["transactions_per_second"].get<double>());
    md += "\n## Buses\n";
    for (const auto& [name, bus] : r["buses"].items()) bus_section(md, name, bus);
    const auto& mem = r["memory"];
    md += fmt::format("\n## Memory\n\n{} B read, {} B written over the bus ports; DRAM busy {} ({}).\n",
                      mem["bytes_read"].get<uint64_t>(), mem["bytes_written"].get<uint64_t>(), ms(mem["busy_s"]),
                      percent(mem["utilisation"]));
    const auto& cpu = r["cpu"];
    md += fmt::format("\n## CPU\n\n{} register reads, {} register writes, {} B read and {} B written through DMI, "
                      "{} cycles of computation, {} interrupt waits ({} asleep).\n",
                      cpu["mmio_reads"].get<uint64_t>(), cpu["mmio_writes"].get<uint64_t>(),
                      cpu["memory_bytes_read"].get<uint64_t>(), cpu["memory_bytes_written"].get<uint64_t>(),
                      cpu["cycles_consumed"].get<uint64_t>(), cpu["irq_waits"].get<uint64_t>(), ms(cpu["irq_wait_s"]));
    md += "\n## Workload\n\n| | |\n|---|---:|\n";
    for (const auto& [key, value] : r["workload"].items()) md += fmt::format("| {} | {} |\n", key, value.dump());
    md += "\n## Files\n\n";
    for (const auto& f : r["outputs"]) md += fmt::format("- `{}`\n", f.get<std::string>());
    return md;
}

void write_file_atomically(const std::string& path, const std::string& content) {
    const std::string partial = path + ".partial";
    {
        std::ofstream out(partial, std::ios::binary | std::ios::trunc);
        out << content;
        if (!out) throw std::runtime_error("cannot write " + partial);
    }
    std::filesystem::rename(partial, path);
}

}  // namespace surfvp
