// The calibration's pieces: the link map and qemu's log read into steps, the fit of a step's
// stream over its units, the prices from the recorded table, and the recorded agreement.
#include <gtest/gtest.h>

#include <set>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "sw/cpu_cost/calibration.h"
#include "sw/cpu_cost/instruction_trace.h"

namespace surfvp::sw {
namespace {

const char* kMap =
    "                0x00001000                surfvp_mark_check\n"
    "                0x00001010                surfvp_mark_interpolation\n"
    "                0x00001020                surfvp_mark_laplacian\n"
    "                0x00001030                surfvp_mark_orientation\n"
    "                0x00001040                surfvp_mark_descriptor\n"
    "                0x00001050                surfvp_mark_idle\n"
    " .text          0x00003000       0x100 /usr/lib/powerpc-linux-gnu/libm.a(s_atan2f.o)\n";

std::string block(uint32_t pc, const std::vector<std::string>& insns) {
    std::ostringstream s;
    s << "----------------\nIN: f\n";
    for (size_t i = 0; i < insns.size(); ++i)
        s << "0x" << std::hex << pc + 4 * i << ":  00000000  " << insns[i] << "\n";
    s << "\n";
    return s.str();
}
std::string exec(uint32_t pc) {
    std::ostringstream s;
    s << "Trace 0: 0x7f0000000000 [00000000/" << std::hex << std::setw(8) << std::setfill('0') << pc
      << "/00006000/00000000] f\n";
    return s.str();
}

TEST(InstructionTrace, CutsTheStreamIntoCandidatesAndSteps) {
    std::istringstream map(kMap);
    const FirmwareLayout layout = read_link_map(map);
    EXPECT_EQ(layout.markers.size(), 6u);
    EXPECT_TRUE(layout.in_libm(0x3004));
    EXPECT_FALSE(layout.in_libm(0x3100));

    std::string log = block(0x1000, {"blr"}) + exec(0x1000) +  // mark check
                      block(0x2000, {"add      r3, r4, r5", "lwz      r6, 0(r1)", "bl       0x3000"}) + exec(0x2000) +
                      block(0x3000, {"fadds    f1, f2, f3", "blr"}) + exec(0x3000) +  // libm
                      block(0x1050, {"blr"}) + exec(0x1050) +                         // idle
                      exec(0x2000);                                                   // outside: not counted
    std::istringstream in(log);
    TraceReplay replay(layout, {PipelineParams{}});
    replay.read(in);
    ASSERT_EQ(replay.candidates().size(), 1u);
    const StepStream& check = replay.candidates()[0][size_t(Step::check)];
    EXPECT_EQ(check.instructions, 1u + 3 + 2);
    EXPECT_EQ(check.mix[size_t(InsnClass::branch)], 3u);
    EXPECT_EQ(check.mix[size_t(InsnClass::fadd)], 1u);
    EXPECT_EQ(check.libm_calls, 1u);
    EXPECT_EQ(check.libm_instructions, 2u);
    // A step lasts from its first issue to the next step's: blr 0 (taken, in the BTAC: the
    // next at 1), add and lwz 1, bl 2 (the next at 3), fadds and blr 3: 3 cycles.
    EXPECT_EQ(check.cycles[0], 3.0);
    EXPECT_EQ(replay.candidates()[0][size_t(Step::descriptor)].instructions, 0u);
    EXPECT_EQ(replay.instructions(), 1u + 3 + 2 + 1 + 3);

    std::istringstream broken("Trace 0: 0x0 [00000000/00009999/0/0] f\n");
    TraceReplay again(layout, {PipelineParams{}});
    EXPECT_THROW(again.read(broken), std::runtime_error);
    std::istringstream no_markers(" .text 0x1 0x2 libm.a(x.o)\n");
    EXPECT_THROW(read_link_map(no_markers), std::runtime_error);
}

// A check step costing 400 + 90 per scan + 35 per compare over candidates that differ is
// fitted back exactly, for every parameter set.
TEST(Calibration, FitRecoversEachUnitsPrice) {
    std::vector<CandidateStream> stream;
    std::vector<std::array<uint64_t, kUnits>> units;
    const size_t sets = calibration_parameter_sets(PipelineParams{}).size();
    for (int c = 0; c < 40; ++c) {
        std::array<uint64_t, kUnits> n{};
        n[size_t(Unit::candidate)] = 1;
        n[size_t(Unit::scan)] = c % 3 != 0;
        n[size_t(Unit::compare)] = n[size_t(Unit::scan)] * uint64_t(1 + c % 7);
        units.push_back(n);
        CandidateStream s;
        for (StepStream& st : s) st.cycles.assign(sets, 0.0);
        const double y = 400 + 90.0 * double(n[size_t(Unit::scan)]) + 35.0 * double(n[size_t(Unit::compare)]);
        s[size_t(Step::check)].cycles.assign(sets, y);
        s[size_t(Step::check)].instructions = uint64_t(y / 2);
        stream.push_back(s);
    }
    const UnitTable t = fit_units(stream, units);
    EXPECT_NEAR(t[size_t(Unit::candidate)].cycles, 400, 1e-6);
    EXPECT_NEAR(t[size_t(Unit::scan)].cycles, 90, 1e-6);
    EXPECT_NEAR(t[size_t(Unit::compare)].cycles, 35, 1e-6);
    EXPECT_NEAR(t[size_t(Unit::compare)].high[0], 35, 1e-6);
    EXPECT_EQ(t[size_t(Unit::descriptor)].cycles, 0);  // no candidate described: no price
    units.pop_back();
    EXPECT_THROW(fit_units(stream, units), std::runtime_error);
}

// The table the build embeds was measured with today's pipeline defaults in each precision
// (else it is stale: rerun `./scripts/bootstrap.sh calibrate`); prices from it are its cycles
// at the defaults, and the linear extrapolation its probes at the probe values, linear between.
TEST(Calibration, RecordedTableMatchesTheModelAndPricesLinearly) {
    const Calibration& c = recorded_calibration();
    for (int precision = 0; precision < 2; ++precision) {
        const PrecisionTable& t = c.precision[size_t(precision)];
        const PipelineParams defaults = PipelineParams::for_precision(precision);
        ASSERT_EQ(t.defaults.size(), pipeline_knobs().size());
        for (size_t k = 0; k < pipeline_knobs().size(); ++k)
            EXPECT_EQ(t.defaults[k], defaults.*pipeline_knobs()[k].field) << pipeline_knobs()[k].key;
        const auto base = unit_prices(surf::HaarMode::rounded, defaults);
        const size_t d = size_t(Unit::descriptor);
        EXPECT_DOUBLE_EQ(base[d], t.haar[1][d].cycles);
        EXPECT_GT(base[d], 50000);  // a descriptor is tens of thousands of instructions
        for (size_t k = 0; k < pipeline_knobs().size(); ++k) {
            const PipelineKnob& knob = pipeline_knobs()[k];
            if (t.high_at[k] == t.defaults[k]) continue;  // not probed upward (fpu.precision; a switch that is on)
            PipelineParams high = defaults, mid = defaults;
            high.*knob.field = t.high_at[k];
            mid.*knob.field = (t.high_at[k] + t.defaults[k]) / 2;
            EXPECT_NEAR(linear_unit_prices(surf::HaarMode::rounded, high)[d], t.haar[1][d].high[k], 1e-6) << knob.key;
            EXPECT_NEAR(linear_unit_prices(surf::HaarMode::rounded, mid)[d], (t.haar[1][d].high[k] + base[d]) / 2, 1e-6)
                << knob.key;
        }
        // Exact wavelets cost more than rounded ones, a slower FPU more than the default.
        EXPECT_GT(unit_prices(surf::HaarMode::exact, defaults)[d], 3 * base[d]);
        PipelineParams slow = defaults;
        slow.fpu_ratio = 3;
        EXPECT_GT(unit_prices(surf::HaarMode::rounded, slow)[d], 1.15 * base[d]);
    }
    // The double-precision FPU's column is slower than the single one's.
    const size_t d = size_t(Unit::descriptor);
    EXPECT_GT(unit_prices(surf::HaarMode::rounded, PipelineParams::for_precision(true))[d],
              1.05 * unit_prices(surf::HaarMode::rounded, PipelineParams::for_precision(false))[d]);
}

// Several knobs at once: at every recorded check point (all the band's knobs moved together,
// the stream re-timed there), the prices from the one-knob probes are within 2 % of the
// stream, per run and Haar mode.
TEST(Calibration, PricesHoldWhereSeveralKnobsMove) {
    const Calibration& c = recorded_calibration();
    std::set<int> points;
    for (const auto& check : c.checks) {
        PipelineParams p;
        for (const PipelineKnob& k : pipeline_knobs()) p.*k.field = check["knobs"][k.key].get<double>();
        const auto prices =
            unit_prices(check["haar"] == "rounded" ? surf::HaarMode::rounded : surf::HaarMode::exact, p);
        double model = 0;
        for (size_t u = 0; u < kUnits; ++u)
            model += check["units_per_keypoint"].value(unit_name(Unit(u)), 0.0) * prices[u];
        const double stream = check["stream_cycles_per_keypoint"];
        EXPECT_NEAR(model / stream, 1.0, 0.02)
            << check["scenario"] << " " << check["haar"] << " point " << check["point"];
        points.insert(check["point"].get<int>());
    }
    EXPECT_GE(points.size(), 5u);
}

// The recorded agreement: on the budget scenario and on castle, in both Haar modes, the
// table's prices (as priced now) against the instruction stream's cycles: within 10 % per
// step (steps above 1 % of the total) and 5 % in total.
TEST(Calibration, RecordedAgreementWithTheInstructionStream) {
    const Calibration& c = recorded_calibration();
    int held = 0;
    for (const auto& run : c.agreement) {
        const std::string scenario = run["scenario"];
        if (scenario != "budget_1024x768" && scenario != "castle_sequence") continue;
        const PipelineParams defaults = PipelineParams::for_precision(run["precision"] == "double");
        const auto prices =
            unit_prices(run["haar"] == "rounded" ? surf::HaarMode::rounded : surf::HaarMode::exact, defaults);
        std::array<double, kSteps> model{};
        for (size_t u = 0; u < kUnits; ++u)
            model[size_t(step_of(Unit(u)))] += run["units_per_keypoint"].value(unit_name(Unit(u)), 0.0) * prices[u];
        double stream_total = 0, model_total = 0;
        for (size_t s = 0; s < kSteps; ++s)
            stream_total += run["steps"][step_name(Step(s))]["stream_cycles_per_keypoint"].get<double>();
        for (size_t s = 0; s < kSteps; ++s) {
            const double stream = run["steps"][step_name(Step(s))]["stream_cycles_per_keypoint"];
            model_total += model[s];
            if (stream > 0.01 * stream_total) {
                EXPECT_NEAR(model[s] / stream, 1.0, 0.10)
                    << scenario << " " << run["haar"] << " " << step_name(Step(s));
            }
        }
        EXPECT_NEAR(model_total / stream_total, 1.0, 0.05) << scenario << " " << run["haar"];
        ++held;
    }
    EXPECT_EQ(held, 8);  // budget and castle, exact and rounded, single and double
}

}  // namespace
}  // namespace surfvp::sw
