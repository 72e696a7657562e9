// The smoke workload: sw/smoke's copy-and-verify software, judged on every copy arriving.
#include <fmt/format.h>

#include "platform/address_map.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/smoke_params.h"
#include "sw/smoke/smoke_software.h"
#include "platform/workload/workload.h"

namespace surfvp {
namespace {

class SmokeWorkload : public Workload {
public:
    explicit SmokeWorkload(const Config& config) {
        config_.intc_base = map::intc.base;
        config_.dma_base = map::dma.base;
        config_.dma_irq = map::irq::dma;
        config_ = smoke_parameter_table().make(config, config_);
        const Bytes memory = memory_params(config).size;
        for (const auto& [key, address] : {std::pair{"smoke.src", config_.src}, std::pair{"smoke.dst", config_.dst}})
            if (address + uint64_t(config_.bytes) > memory.n)
                throw ConfigError(fmt::format("{} {:#x} + smoke.buffer {} B runs past memory.size {}", key, address,
                                              config_.bytes, format_bytes(memory)));
        if (config_.src < config_.dst + config_.bytes && config_.dst < config_.src + config_.bytes)
            throw ConfigError("smoke.src and smoke.dst buffers overlap");
    }

    Ppc440::Software software() override {
        return [this](sw::Hal& hal) { sw::run_smoke(hal, config_, result_); };
    }

    Progress progress() const override { return {result_.copies_done, config_.copies, "copies"}; }

    std::vector<Check> checks() const override {
        std::vector<Check> checks;
        checks.push_back({"copies verified", result_.copies_verified == config_.copies,
                          fmt::format("{} of {} copies of {} B arrived intact", result_.copies_verified, config_.copies,
                                      config_.bytes)});
        checks.push_back({"interrupts and status as expected", result_.problems.empty(),
                          result_.problems.empty() ? "every copy raised the DMA interrupt with a clean status"
                                                   : fmt::format("{}", fmt::join(result_.problems, "; "))});
        return checks;
    }

    nlohmann::ordered_json report() const override {
        return {{"buffer_bytes", config_.bytes},
                {"copies", config_.copies},
                {"copies_verified", result_.copies_verified},
                {"bytes_copied", uint64_t(result_.copies_done) * config_.bytes},
                {"status_polls", result_.polls},
                {"polls_that_saw_busy", result_.busy_seen}};
    }

private:
    sw::SmokeConfig config_;
    sw::SmokeResult result_;
};

}  // namespace

std::unique_ptr<Workload> make_workload(const Config& config) {
    const std::string name = run_settings(config).workload;
    if (name == "smoke") return std::make_unique<SmokeWorkload>(config);
    if (name == "surf") return make_surf_workload(config);
    throw ConfigError("run.workload: no workload named " + name);
}

}  // namespace surfvp
