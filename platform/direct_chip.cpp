#include "direct_chip.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <stdexcept>

#include "address_map.h"
#include "models/common/byte_order.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/local_max_finder.h"
#include "models/iig/iig_regs.h"
#include "models/iig/integral_core.h"
#include "models/intc/intc_regs.h"
#include "soc.h"

namespace surfvp {
namespace f = fhg_regs;

DirectChip::DirectChip(const Config& config, unsigned accelerators)
    : memory_size_(config.bytes("memory.size").n),
      memory_(static_cast<uint8_t*>(std::calloc(memory_size_, 1)), std::free),
      pairs_(accelerators),
      sum_bits_(config.bits("iig.sum_bits")),
      iig_max_width_(unsigned(config.count("iig.max_width"))),
      iig_max_height_(unsigned(config.count("iig.max_height"))),
      fhg_max_width_(unsigned(config.count("fhg.max_width"))),
      fhg_max_height_(unsigned(config.count("fhg.max_height"))),
      core_(fhg_params(config).precision),
      fill_cycles_(uncontended_fill(config).to_seconds() * config.frequency("cpu.clock").hz) {
    if (!memory_) throw std::runtime_error("direct mode: cannot allocate the memory");
}

bool DirectChip::in_memory(uint64_t address, uint64_t bytes) const { return address + bytes <= memory_size_; }

uint8_t* DirectChip::backdoor(uint64_t address, uint64_t bytes) {
    if (!in_memory(address, bytes)) throw std::out_of_range(fmt::format("direct memory: {:#x} +{} B", address, bytes));
    return memory_.get() + address;
}

void DirectChip::read(uint32_t address, void* data, size_t bytes) {
    if (!in_memory(address, bytes)) throw sw::BusError(fmt::format("memory read at {:#010x}", address), address);
    std::memcpy(data, memory_.get() + address, bytes);
}

void DirectChip::write(uint32_t address, const void* data, size_t bytes) {
    if (!in_memory(address, bytes)) throw sw::BusError(fmt::format("memory write at {:#010x}", address), address);
    std::memcpy(memory_.get() + address, data, bytes);
}

const uint8_t* DirectChip::map(uint32_t address, size_t bytes) {
    if (!in_memory(address, bytes)) throw sw::BusError(fmt::format("no memory at {:#010x}", address), address);
    return memory_.get() + address;
}

uint64_t DirectChip::compute(uint64_t cycles, const std::vector<sw::LineTransfer>& lines) {
    size_t fills = 0;
    for (const sw::LineTransfer& line : lines) fills += !line.write_back;
    const uint64_t spent = cycles + uint64_t(std::llround(double(fills) * fill_cycles_));
    cycles_ += spent;
    return spent;
}

uint32_t DirectChip::pending() const {
    if (!(mer_ & intc::MER_HIE)) return 0;
    uint32_t lines = 0;
    for (unsigned k = 0; k < pairs_.size(); ++k) {
        const Iig& i = pairs_[k].iig;
        const Fhg& h = pairs_[k].fhg;
        if ((i.ctrl & iig::CTRL_IRQ_EN) && (i.status & (iig::STATUS_DONE | iig::STATUS_ERROR))) lines |= 1u << map::irq::iig(k);
        const bool done = (h.ctrl & f::CTRL_IRQ_EN_DONE) && (h.status & (f::STATUS_DONE | f::STATUS_ERROR));
        const bool fifo = (h.ctrl & f::CTRL_IRQ_EN_FIFO) && h.fifo_threshold && h.fifo.size() >= h.fifo_threshold;
        if (done || fifo) lines |= 1u << map::irq::fhg(k);
    }
    return lines & ier_;
}

bool DirectChip::irq_pending() { return (mer_ & intc::MER_ME) && pending() != 0; }

void DirectChip::wait_for_irq() {
    if (!irq_pending())
        throw std::runtime_error("direct mode: the software waits for an interrupt that nothing can raise");
}

uint32_t DirectChip::read32(uint32_t address) {
    uint32_t value = 0;
    if (!access(address, value, false)) throw sw::BusError(fmt::format("no register at {:#010x}", address), address);
    return value;
}

void DirectChip::write32(uint32_t address, uint32_t value) {
    if (!access(address, value, true)) throw sw::BusError(fmt::format("no register at {:#010x}", address), address);
}

bool DirectChip::access(uint32_t address, uint32_t& value, bool write) {
    if (address >= map::intc.base && address < map::intc.base + map::intc.size) {
        const uint32_t offset = address - map::intc.base;
        if (write) {
            if (offset == intc::IER) ier_ = value;
            else if (offset == intc::MER) mer_ = value | (mer_ & intc::MER_HIE);
            return offset == intc::IER || offset == intc::MER || offset == intc::IAR;  // IAR: lines are levels here
        }
        value = offset == intc::IPR ? pending() : offset == intc::IER ? ier_ : offset == intc::MER ? mer_ : 0;
        return true;
    }
    for (unsigned k = 0; k < pairs_.size(); ++k) {
        if (address - map::iig_base(k) < map::iig.size) return access_iig(pairs_[k], address - map::iig_base(k), value, write);
        if (address - map::fhg_base(k) < map::fhg.size) return access_fhg(pairs_[k], address - map::fhg_base(k), value, write);
    }
    return false;
}

bool DirectChip::access_iig(Pair& p, uint32_t offset, uint32_t& value, bool write) {
    Iig& r = p.iig;
    uint32_t* field = nullptr;
    switch (offset) {
        case iig::SRC: field = &r.src; break;
        case iig::DST: field = &r.dst; break;
        case iig::WIDTH: field = &r.width; break;
        case iig::HEIGHT: field = &r.height; break;
        case iig::SRC_STRIDE: field = &r.src_stride; break;
        case iig::DST_STRIDE: field = &r.dst_stride; break;
        case iig::CTRL: field = &r.ctrl; break;
        case iig::STATUS: case iig::ERROR_CODE: case iig::STALL_CYCLES: break;
        default: return false;
    }
    if (!write) {
        value = offset == iig::STATUS ? r.status : offset == iig::ERROR_CODE ? r.error : field ? *field : 0;
        return true;
    }
    if (offset == iig::STATUS) r.status &= ~(value & (iig::STATUS_DONE | iig::STATUS_ERROR));
    else if (offset == iig::CTRL) {
        r.ctrl = value & (iig::CTRL_IRQ_EN | iig::CTRL_STREAM);
        if (value & iig::CTRL_START) run_frame(p);
    } else if (field) *field = value;
    return true;
}

bool DirectChip::access_fhg(Pair& p, uint32_t offset, uint32_t& value, bool write) {
    Fhg& r = p.fhg;
    uint32_t* field = nullptr;
    switch (offset) {
        case f::DET_ADDR: field = &r.det; break;
        case f::WIDTH: field = &r.width; break;
        case f::HEIGHT: field = &r.height; break;
        case f::THRESHOLD: field = &r.threshold; break;
        case f::FIFO_THRESHOLD: field = &r.fifo_threshold; break;
        case f::CTRL: field = &r.ctrl; break;
        case f::STATUS: case f::ERROR_CODE: case f::FIFO_DATA: case f::FIFO_LEVEL: case f::OVERFLOW_COUNT:
        case f::CANDIDATES: case f::DET_FRAC_BITS: case f::DET_BYTES: break;
        default: return false;
    }
    if (!write) {
        switch (offset) {
            case f::STATUS:
                value = r.status | (r.fifo_threshold && r.fifo.size() >= r.fifo_threshold ? f::STATUS_FIFO_IRQ : 0);
                break;
            case f::ERROR_CODE: value = r.error; break;
            case f::FIFO_LEVEL: value = uint32_t(r.fifo.size()); break;
            case f::OVERFLOW_COUNT: value = 0; break;
            case f::CANDIDATES: value = r.candidates; break;
            case f::DET_FRAC_BITS: value = core_.precision().det_frac_bits; break;
            case f::DET_BYTES: value = f::det_bytes_for(core_.precision().det_bits); break;
            case f::FIFO_DATA:
                value = r.fifo.empty() ? 0 : r.fifo.front();
                if (!r.fifo.empty()) r.fifo.pop_front();
                break;
            default: value = *field;
        }
        return true;
    }
    if (offset == f::STATUS) r.status &= ~(value & (f::STATUS_DONE | f::STATUS_ERROR | f::STATUS_FIFO_OVERFLOW));
    else if (offset == f::CTRL) {
        r.ctrl = value & (f::CTRL_IRQ_EN_DONE | f::CTRL_IRQ_EN_FIFO);
        if (value & f::CTRL_ABORT) {
            if (r.running) {
                r.running = false;
                r.error = f::ERR_ABORTED;
                r.status = f::STATUS_ERROR;
            }
        } else if ((value & f::CTRL_START) && r.running) {
            r.error = f::ERR_START_BUSY;
            r.status |= f::STATUS_ERROR;
        } else if (value & f::CTRL_START) {
            const bool size_ok = r.width && r.height && r.width <= fhg_max_width_ && r.height <= fhg_max_height_;
            r.running = size_ok;
            r.fifo.clear();
            r.candidates = 0;
            r.status = size_ok ? f::STATUS_BUSY : f::STATUS_ERROR;
            if (!size_ok) r.error = f::ERR_SIZE;
        }
    } else if (field) *field = value;
    return true;
}

// An IIG START: the whole frame at once, through the FHG when it listens.
void DirectChip::run_frame(Pair& p) {
    Iig& i = p.iig;
    Fhg& h = p.fhg;
    auto iig_error = [&](uint32_t code) {
        i.error = code;
        i.status = iig::STATUS_ERROR;
    };
    if (!i.width || !i.height || i.width > iig_max_width_ || i.height > iig_max_height_) return iig_error(iig::ERR_SIZE);
    const uint32_t src_stride = i.src_stride ? i.src_stride : i.width, dst_stride = i.dst_stride ? i.dst_stride : 4 * i.width;
    if (!in_memory(i.src, uint64_t(src_stride) * (i.height - 1) + i.width)) return iig_error(iig::ERR_READ);
    if (!in_memory(i.dst, uint64_t(dst_stride) * (i.height - 1) + 4ull * i.width)) return iig_error(iig::ERR_WRITE);
    std::vector<uint32_t> integral(size_t(i.width) * i.height);
    const IntegralCore integral_core(sum_bits_);
    for (uint32_t y = 0; y < i.height; ++y) {
        const uint32_t* above = y ? &integral[size_t(y - 1) * i.width] : nullptr;
        if (!integral_core.row(memory_.get() + i.src + size_t(y) * src_stride, above, &integral[size_t(y) * i.width], int(i.width)))
            return iig_error(iig::ERR_OVERFLOW);
        uint8_t* out = memory_.get() + i.dst + size_t(y) * dst_stride;
        for (uint32_t x = 0; x < i.width; ++x) store_be32(out + 4 * x, integral[size_t(y) * i.width + x]);
    }
    i.status = iig::STATUS_DONE;
    if (!(i.ctrl & iig::CTRL_STREAM) || !h.running) return;
    if (h.width != i.width || h.height != i.height) {
        h.running = false;
        h.error = f::ERR_PIXELBUS;
        h.status = f::STATUS_ERROR;
        return;
    }
    const IntegralView view{integral.data(), int(i.width), int(i.height), i.width};
    const uint32_t blocks_x = (i.width + 1) / 2, blocks_y = (i.height + 1) / 2;
    std::vector<int32_t> records(size_t(blocks_x) * fhg::kDeterminantsPerBlock);
    std::vector<fhg::Candidate> found;
    const fhg::LocalMaxFinder finder(int32_t(h.threshold));
    for (uint32_t by = 0; by < blocks_y; ++by) {
        core_.block_row(view, int(by), records.data());
        finder.block_row(records.data(), int(blocks_x), int(by), found);
        const uint32_t n = f::det_bytes_for(core_.precision().det_bits);
        const uint64_t at = h.det + uint64_t(by) * blocks_x * f::record_bytes(n);
        if (!in_memory(at, records.size() * n)) {
            h.running = false;
            h.error = f::ERR_WRITE;
            h.status = f::STATUS_ERROR;
            return;
        }
        for (size_t k = 0; k < records.size(); ++k) f::store_det(memory_.get() + at + n * k, records[k], n);
    }
    for (const fhg::Candidate& c : found) h.fifo.push_back(fhg::pack_candidate(c));
    h.candidates = uint32_t(found.size());
    h.running = false;
    h.status = f::STATUS_DONE;
}

}  // namespace surfvp
