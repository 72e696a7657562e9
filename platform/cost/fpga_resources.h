#pragma once
// The FPGA resources a configuration needs, derived from its modelled structure (docs/resources.md):
// block RAMs (RAMB36) for the FHG's line FIFO, maxima FIFO, sequence memory and determinant row
// buffers and the IIG's line buffers; DSP48E slices for HessianCalc's multipliers at the
// configured widths and the APU FPU; LUTs and flip-flops per block from stated per-bit
// assumptions; against the device's capacity (fpga.*), so a configuration that does not fit
// says so. Plain C++ on the configuration.
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "platform/scenario/config.h"

namespace surfvp {

// The device the resources are counted against, and what the estimate cannot derive: one IP
// block's PLB interfaces and the rest of the system (fpga.*).
struct FpgaDevice {
    std::string device;  // fpga.device, by name
    uint64_t ramb36 = 0, dsp48e = 0, slices = 0;
    Frequency bram_fmax;
    double max_utilisation = 0.85, max_block_utilisation = 1;  // of the LUTs and FFs; of the RAMB36 and DSP48E
    uint64_t ip_interface_luts = 0, ip_interface_ffs = 0;
    uint64_t infrastructure_luts = 0, infrastructure_ffs = 0, infrastructure_ramb36 = 0;

    static const ParamTable<FpgaDevice>& parameter_table();
};
FpgaDevice fpga_device(const ParamValues& values);

struct BlockResources {
    std::string block;  // "fhg (x2)": a pair's blocks count once per pair
    double ramb36 = 0, dsp48e = 0, luts = 0, ffs = 0;
    std::string basis;  // how the figures were reached, in words
};

// One FHG's parts as the model estimates them, each on its own so that a synthesis of the
// Verilog reference (surfvp synthesize) can stand beside it. The TripleMAC is one of
// fhg.triple_macs. line_fifo is its BRAMs with their port logic, line_routing what takes the
// bus lanes' reads to their ports and the values back (and the write side's counters).
struct FhgParts {
    BlockResources line_fifo, sequence_memory, maxima_fifo, det_rows;  // block RAM
    BlockResources line_routing, triple_mac, hessian_calc, local_max_finder, control;
};
FhgParts fhg_parts(const Config& config);

struct FpgaResources {
    std::string device;
    double ramb36_capacity = 0, dsp48e_capacity = 0, lut_capacity = 0, ff_capacity = 0;
    double max_utilisation = 1, max_block_utilisation = 1;  // fpga.max_utilisation, fpga.max_block_utilisation
    std::vector<BlockResources> blocks;
    BlockResources total;
    // The resources the configuration needs more of than the device can give it, the placement
    // margin kept: "LUT: 43742 of 44800 (98 %), above the 85 % that places and routes
    // (fpga.max_utilisation)", or "RAMB36: 164 of 148 (111 %), more than the device has".
    std::vector<std::string> over;
    bool fits() const { return over.empty(); }
};

// RAMB36 for `words` words of `bits` bits in the RAMB36's aspect ratios (32Kx1 .. 1Kx36, and
// 512x72 simple dual-port): columns of the widest mode that holds the width, times rows.
unsigned ramb36_for(unsigned long words, unsigned bits);
// DSP48E for a signed `a` x `b`-bit product: 25x18 per slice, tiled.
unsigned dsp48e_for(unsigned a, unsigned b);

FpgaResources fpga_resources(const Config& config);
nlohmann::ordered_json resources_json(const FpgaResources& resources);

}  // namespace surfvp
