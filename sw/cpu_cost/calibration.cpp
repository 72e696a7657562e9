#include "sw/cpu_cost/calibration.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <stdexcept>

namespace surfvp::sw {

extern const char* const kRecordedCalibrationJson;  // calibration_data.cpp, generated from calibration.json

namespace {

size_t knobs() { return pipeline_knobs().size(); }

nlohmann::ordered_json unit_to_json(const UnitCalibration& u) {
    nlohmann::ordered_json mix = nlohmann::ordered_json::object();
    for (size_t c = 0; c < kInsnClasses; ++c)
        if (u.mix[c] > 0) mix[insn_class_name(InsnClass(c))] = u.mix[c];
    nlohmann::ordered_json low = nlohmann::ordered_json::object(), high = nlohmann::ordered_json::object();
    for (size_t k = 0; k < knobs(); ++k) {
        low[pipeline_knobs()[k].key] = u.low[k];
        high[pipeline_knobs()[k].key] = u.high[k];
    }
    return {{"cycles", u.cycles},
            {"instructions", u.instructions},
            {"libm_calls", u.libm_calls},
            {"libm_instructions", u.libm_instructions},
            {"mix", mix},
            {"cycles_low", low},
            {"cycles_high", high}};
}

UnitCalibration unit_from_json(const nlohmann::ordered_json& j) {
    UnitCalibration u;
    u.cycles = j.at("cycles").get<double>();
    u.instructions = j.at("instructions").get<double>();
    u.libm_calls = j.at("libm_calls").get<double>();
    u.libm_instructions = j.at("libm_instructions").get<double>();
    for (size_t c = 0; c < kInsnClasses; ++c) u.mix[c] = j.at("mix").value(insn_class_name(InsnClass(c)), 0.0);
    for (const PipelineKnob& k : pipeline_knobs()) {
        u.low.push_back(j.at("cycles_low").at(k.key).get<double>());
        u.high.push_back(j.at("cycles_high").at(k.key).get<double>());
    }
    return u;
}

constexpr const char* kHaarNames[2] = {"exact", "rounded"};
constexpr const char* kPrecisionNames[2] = {"single", "double"};

nlohmann::ordered_json sample_to_json(const StreamSample& s) {
    nlohmann::ordered_json blocks = nlohmann::ordered_json::array();
    for (const StreamSample::Block& b : s.blocks)
        blocks.push_back({{"pc", b.pc}, {"marker", b.marker}, {"libm", b.libm}, {"code", b.code}});
    return {{"blocks", blocks}, {"sequence", s.sequence}};
}

StreamSample sample_from_json(const nlohmann::ordered_json& j) {
    StreamSample s;
    for (const auto& b : j.at("blocks"))
        s.blocks.push_back({b.at("pc").get<uint32_t>(), b.at("marker").get<int>(), b.at("libm").get<bool>(),
                            b.at("code").get<std::vector<std::string>>()});
    s.sequence = j.at("sequence").get<std::vector<uint32_t>>();
    for (uint32_t i : s.sequence)
        if (i >= s.blocks.size())
            throw std::runtime_error("calibration table: the sample runs a block it does not have");
    return s;
}

// Least squares of y over a step's units (the columns of x), over the candidates; a unit no
// candidate did costs 0.
std::vector<double> solve(const Eigen::MatrixXd& x, const std::vector<double>& y) {
    std::vector<int> used;
    for (int c = 0; c < x.cols(); ++c)
        if (x.col(c).squaredNorm() > 0) used.push_back(c);
    std::vector<double> out(size_t(x.cols()), 0.0);
    if (used.empty()) return out;
    Eigen::MatrixXd a(x.rows(), Eigen::Index(used.size()));
    for (size_t i = 0; i < used.size(); ++i) a.col(Eigen::Index(i)) = x.col(used[i]);
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(y.data(), Eigen::Index(y.size()));
    const Eigen::VectorXd per = a.colPivHouseholderQr().solve(b);
    for (size_t i = 0; i < used.size(); ++i) out[size_t(used[i])] = per(Eigen::Index(i));
    return out;
}

}  // namespace

const Calibration& recorded_calibration() {
    static const Calibration c = calibration_from_json(nlohmann::ordered_json::parse(kRecordedCalibrationJson));
    return c;
}

nlohmann::ordered_json calibration_to_json(const Calibration& c) {
    nlohmann::ordered_json out = {{"provenance", c.provenance}};
    for (size_t p = 0; p < 2; ++p) {
        const PrecisionTable& t = c.precision[p];
        nlohmann::ordered_json defaults = nlohmann::ordered_json::object(), probes = nlohmann::ordered_json::object();
        for (size_t k = 0; k < knobs(); ++k) {
            defaults[pipeline_knobs()[k].key] = t.defaults[k];
            probes[pipeline_knobs()[k].key] = {t.low_at[k], t.high_at[k]};
        }
        nlohmann::ordered_json haar = nlohmann::ordered_json::object();
        for (size_t h = 0; h < 2; ++h) {
            nlohmann::ordered_json units = nlohmann::ordered_json::object();
            for (size_t u = 0; u < kUnits; ++u) units[unit_name(Unit(u))] = unit_to_json(t.haar[h][u]);
            haar[kHaarNames[h]] = units;
        }
        out[kPrecisionNames[p]] = {{"defaults", defaults}, {"probes", probes}, {"haar", haar}};
    }
    out["agreement"] = c.agreement;
    out["checks"] = c.checks;
    nlohmann::ordered_json samples = nlohmann::ordered_json::object();
    nlohmann::ordered_json msurf_samples = nlohmann::ordered_json::object();
    for (size_t h = 0; h < 2; ++h) {
        samples[kHaarNames[h]] = sample_to_json(c.sample[h]);
        if (!c.msurf_sample[h].empty()) msurf_samples[kHaarNames[h]] = sample_to_json(c.msurf_sample[h]);
    }
    out["sample"] = samples;
    if (!msurf_samples.empty()) out["msurf_sample"] = msurf_samples;
    return out;
}

Calibration calibration_from_json(const nlohmann::ordered_json& j) {
    try {
        Calibration c;
        c.provenance = j.at("provenance");
        c.agreement = j.value("agreement", nlohmann::ordered_json::array());
        c.checks = j.value("checks", nlohmann::ordered_json::array());
        if (j.contains("sample"))
            for (size_t h = 0; h < 2; ++h) c.sample[h] = sample_from_json(j.at("sample").at(kHaarNames[h]));
        if (j.contains("msurf_sample"))
            for (size_t h = 0; h < 2; ++h) c.msurf_sample[h] = sample_from_json(j.at("msurf_sample").at(kHaarNames[h]));
        for (size_t p = 0; p < 2; ++p) {
            const nlohmann::ordered_json& in = j.at(kPrecisionNames[p]);
            PrecisionTable& t = c.precision[p];
            for (const PipelineKnob& k : pipeline_knobs()) {
                t.defaults.push_back(in.at("defaults").at(k.key).get<double>());
                t.low_at.push_back(in.at("probes").at(k.key).at(0).get<double>());
                t.high_at.push_back(in.at("probes").at(k.key).at(1).get<double>());
            }
            for (size_t h = 0; h < 2; ++h)
                for (size_t u = 0; u < kUnits; ++u) {
                    const nlohmann::ordered_json& units = in.at("haar").at(kHaarNames[h]);
                    if (units.contains(unit_name(Unit(u)))) {
                        t.haar[h][u] = unit_from_json(units.at(unit_name(Unit(u))));
                    } else {  // a table from before the unit existed: no price (0), as for a unit never done
                        t.haar[h][u].low = t.haar[h][u].high = std::vector<double>(knobs(), 0.0);
                    }
                }
        }
        return c;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(std::string("calibration table: ") + e.what());
    }
}

std::vector<std::array<double, kSteps>> sample_cycles(const StreamSample& sample,
                                                      const std::vector<PipelineParams>& sets) {
    FirmwareLayout none;
    TraceReplay replay(none, sets);
    replay.replay(sample);
    std::vector<std::array<double, kSteps>> out(sets.size(), std::array<double, kSteps>{});
    for (const CandidateStream& c : replay.candidates())
        for (size_t st = 0; st < kSteps; ++st)
            for (size_t k = 0; k < sets.size(); ++k) out[k][st] += c[st].cycles[k];
    return out;
}

std::array<double, kUnits> unit_prices(surf::HaarMode haar, const PipelineParams& params, const Calibration& c) {
    const size_t h = haar == surf::HaarMode::rounded ? 1 : 0;
    const PrecisionTable& t = c.precision[params.double_precision > 0.5 ? 1 : 0];
    PipelineParams defaults = params;
    bool moved = false;
    for (size_t k = 0; k < knobs(); ++k) {
        moved |= params.*pipeline_knobs()[k].field != t.defaults[k];
        defaults.*pipeline_knobs()[k].field = t.defaults[k];
    }
    std::array<double, kUnits> prices{};
    for (size_t u = 0; u < kUnits; ++u) prices[u] = t.haar[h][u].cycles;
    if (!moved) return prices;
    if (c.sample[h].empty()) throw std::runtime_error("calibration table: no stream sample to re-time");
    const auto cycles = sample_cycles(c.sample[h], {defaults, params});
    // msurf, when its run kept a sample, is scaled by that one: its mix is not Bay's.
    const auto msurf_cycles = c.msurf_sample[h].empty() ? cycles : sample_cycles(c.msurf_sample[h], {defaults, params});
    for (size_t u = 0; u < kUnits; ++u) {
        const auto& by = Unit(u) == Unit::msurf ? msurf_cycles : cycles;
        const size_t st = size_t(step_of(Unit(u)));
        if (by[0][st] > 0) prices[u] *= by[1][st] / by[0][st];
    }
    return prices;
}

std::array<double, kUnits> linear_unit_prices(surf::HaarMode haar, const PipelineParams& params, const Calibration& c) {
    const PrecisionTable& t = c.precision[params.double_precision > 0.5 ? 1 : 0];
    const UnitTable& table = t.haar[haar == surf::HaarMode::rounded ? 1 : 0];
    std::array<double, kUnits> prices{};
    for (size_t u = 0; u < kUnits; ++u) {
        const UnitCalibration& unit = table[u];
        double cycles = unit.cycles;
        for (size_t k = 0; k < knobs(); ++k) {
            const double v = params.*pipeline_knobs()[k].field, d = t.defaults[k];
            if (v > d && t.high_at[k] > d) cycles += (unit.high[k] - unit.cycles) * (v - d) / (t.high_at[k] - d);
            if (v < d && t.low_at[k] < d) cycles += (unit.low[k] - unit.cycles) * (d - v) / (d - t.low_at[k]);
        }
        prices[u] = std::max(0.0, cycles);
    }
    return prices;
}

std::pair<double, double> probe_values(const PipelineKnob& knob, double base) {
    if (std::string(knob.key) == "fpu.precision") return {base, base};
    if (knob_choice(knob, base)) return base > 0.5 ? std::pair{0.0, base} : std::pair{base, 1.0};
    const double span = knob.high - knob.low;
    const double low =
        knob.low < base ? knob.low : std::max(std::string(knob.unit) == "count" ? 1.0 : 0.0, base - span);
    const double high = knob.high > base ? knob.high : base + span;
    return {low, high};
}

std::vector<PipelineParams> calibration_parameter_sets(const PipelineParams& base) {
    std::vector<PipelineParams> sets{base};
    for (const PipelineKnob& k : pipeline_knobs()) {
        const auto [low, high] = probe_values(k, base.*k.field);
        for (double v : {low, high}) {
            PipelineParams p = base;
            p.*k.field = v;
            sets.push_back(p);
        }
    }
    return sets;
}

UnitTable fit_units(const std::vector<CandidateStream>& stream, const std::vector<std::array<uint64_t, kUnits>>& units,
                    size_t first_set, bool probed) {
    if (stream.size() != units.size())
        throw std::runtime_error("calibration: the trace has " + std::to_string(stream.size()) +
                                 " candidates, the native stage " + std::to_string(units.size()));
    UnitTable table;
    for (UnitCalibration& u : table) u.low.assign(knobs(), 0.0), u.high.assign(knobs(), 0.0);
    for (size_t s = 0; s < kSteps; ++s) {
        std::vector<Unit> own;
        for (size_t u = 0; u < kUnits; ++u)
            if (step_of(Unit(u)) == Step(s)) own.push_back(Unit(u));
        Eigen::MatrixXd x(Eigen::Index(units.size()), Eigen::Index(own.size()));
        for (size_t c = 0; c < units.size(); ++c)
            for (size_t i = 0; i < own.size(); ++i)
                x(Eigen::Index(c), Eigen::Index(i)) = double(units[c][size_t(own[i])]);
        auto fit = [&](auto value, auto store) {
            std::vector<double> y;
            for (const CandidateStream& c : stream) y.push_back(value(c[s]));
            const std::vector<double> per = solve(x, y);
            for (size_t i = 0; i < own.size(); ++i) store(table[size_t(own[i])], per[i]);
        };
        fit([&](const StepStream& st) { return st.cycles[first_set]; },
            [](UnitCalibration& u, double v) { u.cycles = v; });
        // The knobs' sensitivities only from a stream timed at their probes too (the caller
        // keeps the recorded ones otherwise).
        for (size_t k = 0; probed && k < knobs(); ++k) {
            fit([&](const StepStream& st) { return st.cycles[first_set + 1 + 2 * k]; },
                [&](UnitCalibration& u, double v) { u.low[k] = v; });
            fit([&](const StepStream& st) { return st.cycles[first_set + 2 + 2 * k]; },
                [&](UnitCalibration& u, double v) { u.high[k] = v; });
        }
        fit([](const StepStream& st) { return double(st.instructions); },
            [](UnitCalibration& u, double v) { u.instructions = v; });
        for (size_t c = 0; c < kInsnClasses; ++c)
            fit([&](const StepStream& st) { return double(st.mix[c]); },
                [&](UnitCalibration& u, double v) { u.mix[c] = v; });
        fit([](const StepStream& st) { return double(st.libm_calls); },
            [](UnitCalibration& u, double v) { u.libm_calls = v; });
        fit([](const StepStream& st) { return double(st.libm_instructions); },
            [](UnitCalibration& u, double v) { u.libm_instructions = v; });
    }
    return table;
}

}  // namespace surfvp::sw
