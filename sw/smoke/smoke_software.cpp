#include "smoke_software.h"

#include <fmt/format.h>

#include "models/dma/dma_regs.h"
#include "models/intc/intc_regs.h"

namespace surfvp::sw {

std::vector<uint8_t> smoke_pattern(uint32_t bytes, unsigned copy) {
    std::vector<uint8_t> data(bytes);
    uint32_t state = 0x9E3779B9u ^ copy;  // xorshift: cheap, deterministic, no repeats per burst
    for (auto& b : data) {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        b = uint8_t(state);
    }
    return data;
}

namespace {

void copy_once(Hal& hal, const SmokeConfig& c, unsigned copy, SmokeResult& result) {
    const std::vector<uint8_t> pattern = smoke_pattern(c.bytes, copy);
    {
        Span span(hal, "fill source");
        hal.write(c.src, pattern.data(), pattern.size());
    }
    {
        Span span(hal, "program dma");
        hal.write32(c.dma_base + dma::SRC, c.src);
        hal.write32(c.dma_base + dma::DST, c.dst);
        hal.write32(c.dma_base + dma::LEN, c.bytes);
        hal.write32(c.dma_base + dma::CTRL, dma::CTRL_START | dma::CTRL_IRQ_EN);
    }
    {
        Span span(hal, "poll status");
        for (unsigned i = 0; i < c.polls; ++i) {
            hal.consume(c.poll_interval);
            ++result.polls;
            if (hal.read32(c.dma_base + dma::STATUS) & dma::STATUS_BUSY) ++result.busy_seen;
        }
    }
    {
        Span span(hal, "wait for dma");
        hal.wait_for_irq();
    }
    Span span(hal, "acknowledge and verify");
    const uint32_t vector = hal.read32(c.intc_base + intc::IVR);
    if (vector != c.dma_irq)
        result.problems.push_back(
            fmt::format("copy {}: INTC vector {} instead of the DMA's {}", copy, vector, c.dma_irq));
    const uint32_t status = hal.read32(c.dma_base + dma::STATUS);
    if (status & dma::STATUS_ERROR)
        result.problems.push_back(fmt::format("copy {}: DMA error code {} at {:#010x}", copy,
                                              hal.read32(c.dma_base + dma::ERROR_CODE),
                                              hal.read32(c.dma_base + dma::ERROR_ADDR)));
    hal.write32(c.dma_base + dma::STATUS, dma::STATUS_DONE | dma::STATUS_ERROR);
    hal.write32(c.intc_base + intc::IAR, 1u << c.dma_irq);
    ++result.copies_done;

    std::vector<uint8_t> copied(c.bytes);
    hal.read(c.dst, copied.data(), copied.size());
    if (copied == pattern)
        ++result.copies_verified;
    else
        result.problems.push_back(fmt::format("copy {}: destination differs from the source", copy));
}

}  // namespace

void run_smoke(Hal& hal, const SmokeConfig& c, SmokeResult& result) {
    {
        Span span(hal, "init intc");
        hal.write32(c.intc_base + intc::IER, 1u << c.dma_irq);
        hal.write32(c.intc_base + intc::MER, intc::MER_ME | intc::MER_HIE);
    }
    for (unsigned copy = 0; copy < c.copies; ++copy) copy_once(hal, c, copy, result);
}

}  // namespace surfvp::sw
