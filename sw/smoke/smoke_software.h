#pragma once
// The smoke scenario's software: the CPU fills a buffer in DDR, has the test DMA copy it
// over PLB2, polls the DMA's status over PLB1 meanwhile, sleeps until the DMA's interrupt
// arrives through the INTC, acknowledges it, and checks the copy byte for byte.
#include <cstdint>
#include <string>
#include <vector>

#include "models/common/hal.h"

namespace surfvp::sw {

struct SmokeConfig {
    uint32_t intc_base = 0;
    uint32_t dma_base = 0;
    unsigned dma_irq = 0;
    uint32_t src = 0;
    uint32_t dst = 0;
    uint32_t bytes = 0;
    unsigned copies = 1;
    unsigned polls = 0;          // status polls per copy before sleeping on the interrupt
    uint64_t poll_interval = 0;  // CPU cycles between polls
};

struct SmokeResult {
    unsigned copies_done = 0;
    unsigned copies_verified = 0;
    unsigned polls = 0;
    unsigned busy_seen = 0;             // polls that found the DMA busy
    std::vector<std::string> problems;  // each failed expectation, in words
};

// Runs all copies; progress is visible through `result` while it runs.
void run_smoke(Hal& hal, const SmokeConfig& config, SmokeResult& result);

// The deterministic fill pattern of copy `copy`.
std::vector<uint8_t> smoke_pattern(uint32_t bytes, unsigned copy);

}  // namespace surfvp::sw
