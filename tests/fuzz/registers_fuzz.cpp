// Fuzz target: the IP blocks' register interfaces as software sees them. Random MMIO
// sequences go into the untimed DirectChip (platform/direct/direct_chip.h), which owns the
// same register classes as the SystemC models (IigRegisters, FhgRegisters, IntcRegisters) and
// runs a START on its own memory: the integral image, the determinants, the maxima FIFO, and
// the DMA address checks of both blocks.
//
// Input: a header byte, then operations until the input ends.
//   header   bits 0-1: soc.accelerators - 1 (1 to 4 pairs); bit 2: memory.size 4 MiB instead
//            of 1 MiB
//   op byte  bits 0-2 the operation, bits 3-4 the window (IIG, FHG, INTC, the standalone DMA's,
//            which direct mode does not have), bits 5-7 the accelerator pair (0-7, beyond
//            soc.accelerators there is no register):
//     0 write32(register, 32-bit value)   1 write32(register, 8-bit value: sizes, codes)
//     2 read32(register)                  3 wait_for_irq()              4 irq_pending()
//     5 write32(any address, value)       6 read32(any address)
//     7 write(address, n bytes): memory, as the driver puts an image there
//   register: one byte, below 0x80 a word offset ((byte & 0x3f) x 4), else the byte itself as
//   the offset (unaligned, or past the registers). Addresses and values: 4 bytes, big-endian.
//
// Expected answers, the model's own: sw::BusError (no register at the address, memory outside
// the installed DDR) and direct mode's "the software waits for an interrupt that nothing can
// raise" (std::runtime_error, "direct mode: ..."). Bad programming otherwise shows as the
// blocks' STATUS.ERROR with ERROR_CODE, never as an exception. Any other exception, a crash, a
// sanitizer report, a hang or an allocation beyond the fuzzer's -malloc_limit_mb is a bug.
//
// Work per input: the configuration is the default one except for two scenario parameters
// the model itself enforces. iig/fhg max_width and max_height are 64: a larger WIDTH or HEIGHT
// is refused with ERROR_CODE SIZE, as a 1025-pixel frame is by default. memory.size is 1 or
// 4 MiB instead of 256 MiB: AddressSanitizer touches all of a 256 MiB calloc, which would make
// 13 inputs a second; the address checks against the installed size are the same code.
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "models/common/hal.h"
#include "platform/address_map.h"
#include "platform/direct/direct_chip.h"

namespace {
using namespace surfvp;

Config chip_config(uint8_t header) {
    Config config;
    for (const char* key : {"iig.max_width", "iig.max_height", "fhg.max_width", "fhg.max_height"})
        config.set(key, "64", "fuzz");
    config.set("soc.accelerators", std::to_string(1 + (header & 3)), "fuzz");
    config.set("memory.size", header & 4 ? "4 MiB" : "1 MiB", "fuzz");
    return config;
}

uint32_t register_address(uint8_t op, uint8_t reg) {
    const unsigned window = (op >> 3) & 3, pair = op >> 5;
    const uint32_t base = window == 0   ? map::iig_base(pair)
                          : window == 1 ? map::fhg_base(pair)
                          : window == 2 ? map::intc.base
                                        : map::dma.base;
    return base + (reg < 0x80 ? (reg & 0x3fu) * 4 : reg);
}

void run(DirectChip& chip, fuzz::Bytes& in) {
    while (!in.empty()) {
        const uint8_t op = in.u8();
        switch (op & 7) {
            case 0: {
                const uint32_t address = register_address(op, in.u8());
                chip.write32(address, in.u32());
                break;
            }
            case 1: {
                const uint32_t address = register_address(op, in.u8());
                chip.write32(address, in.u8());
                break;
            }
            case 2:
                chip.read32(register_address(op, in.u8()));
                break;
            case 3:
                chip.wait_for_irq();
                break;
            case 4:
                chip.irq_pending();
                break;
            case 5: {
                const uint32_t address = in.u32();
                chip.write32(address, in.u32());
                break;
            }
            case 6:
                chip.read32(in.u32());
                break;
            case 7: {
                const uint32_t address = in.u32();
                std::vector<uint8_t> bytes(1 + in.u8() % 64);
                for (uint8_t& b : bytes) b = in.u8();
                chip.write(address, bytes.data(), bytes.size());
                break;
            }
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::Bytes in(data, size);
    const uint8_t header = in.u8();
    const Config config = chip_config(header);
    DirectChip chip(config, unsigned(config.count("soc.accelerators")));
    try {
        run(chip, in);
    } catch (const sw::BusError&) {
        // the bus's answer: no register or no memory at the address
    } catch (const std::runtime_error& e) {
        if (std::string_view(e.what()).rfind("direct mode: ", 0) != 0) fuzz::unexpected(e);
        // direct mode's answer to software that waits for an interrupt nothing can raise
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
