#include "platform/report/section_statistics.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace surfvp {
using Json = nlohmann::ordered_json;

const std::vector<SectionStatistics>& report_statistics() {
    static const std::vector<SectionStatistics> sections{
        {"SSA FHG",
         "fhg",
         {"cycles_per_block", "block_limit", "busy_s", "computing_s", "waiting_for_lines_s", "waiting_for_writer_s",
          "line_fifo_high_water", "maxima_fifo_high_water", "candidates", "candidates_dropped", "errors"}},
        {"SSA IIG",
         "iig",
         {"busy_s", "computing_s", "waiting_for_image_s", "blocked_by_write_s", "blocked_by_pixelbus_s",
          "send_stalled_s", "errors"}},
        {"CPU (PPC440)",
         "cpu",
         {"mmio_reads", "mmio_writes", "cycles_consumed", "irq_waits", "irq_wait_s", "memory.path", "memory.bytes_read",
          "memory.line_fills", "memory.bytes_written", "memory.write_backs", "memory.fill_stall_s",
          "memory.ddr_wait_s"}},
        {"Buses",
         "buses.*",
         {"width_bits", "clock_hz", "read.bursts", "read.bytes", "read.busy_s", "read.utilisation", "write.bursts",
          "write.bytes", "write.busy_s", "write.utilisation", "masters.*.bursts", "masters.*.errors",
          "masters.*.bursts_by_wait_cycles", "masters.*.bytes_read", "masters.*.bytes_written", "masters.*.busy_s",
          "masters.*.wait_s", "masters.*.max_wait_s"}},
        {"DDR",
         "memory",
         {"bytes_read", "bytes_written", "busy_s", "utilisation", "ports.*.reads", "ports.*.writes",
          "ports.*.bytes_read", "ports.*.bytes_written", "ports.*.wait_s"}},
    };
    return sections;
}

const SectionStatistics& section_statistics(std::string_view section) {
    for (const SectionStatistics& s : report_statistics())
        if (s.section == section) return s;
    throw std::logic_error(fmt::format("report.md has no section '{}' with statistics", section));
}

const Json& Shown::operator[](std::string_view leaf) const {
    const std::string listed = prefix_ + std::string(leaf);
    if (std::find(section_.leaves.begin(), section_.leaves.end(), listed) == section_.leaves.end())
        throw std::logic_error(
            fmt::format("report.md's section '{}' shows {}.{}, which its list of statistics "
                        "(platform/report/section_statistics.cpp) does not name",
                        section_.section, section_.node, listed));
    static const Json null;
    const Json* at = &node_;
    for (size_t from = 0;;) {
        const size_t dot = leaf.find('.', from);
        const std::string level(leaf.substr(from, dot == std::string_view::npos ? leaf.npos : dot - from));
        if (!at->is_object() || !at->contains(level)) return null;
        at = &(*at)[level];
        if (dot == std::string_view::npos) return *at;
        from = dot + 1;
    }
}

double Shown::number(std::string_view leaf) const {
    const Json& v = (*this)[leaf];
    return v.is_number() ? v.get<double>() : 0.0;
}
uint64_t Shown::count(std::string_view leaf) const {
    const Json& v = (*this)[leaf];
    return v.is_number_unsigned() ? v.get<uint64_t>() : v.is_number() ? uint64_t(std::max(0.0, v.get<double>())) : 0;
}
std::string Shown::text(std::string_view leaf) const {
    const Json& v = (*this)[leaf];
    return v.is_string() ? v.get<std::string>() : "";
}

std::vector<std::pair<std::string, Shown>> Shown::each(std::string_view level) const {
    std::vector<std::pair<std::string, Shown>> out;
    const std::string key(level);
    if (node_.is_object() && node_.contains(key) && node_[key].is_object())
        for (const auto& [name, child] : node_[key].items())
            out.emplace_back(name, Shown(child, section_, prefix_ + key + ".*."));
    return out;
}

}  // namespace surfvp
