#include "sw/cpu_cost/calibration.h"

#include <cmath>

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
    return {{"cycles", u.cycles},       {"instructions", u.instructions}, {"libm_calls", u.libm_calls},
            {"libm_instructions", u.libm_instructions}, {"mix", mix}, {"cycles_low", low}, {"cycles_high", high}};
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
    nlohmann::ordered_json defaults = nlohmann::ordered_json::object();
    for (size_t k = 0; k < knobs(); ++k) defaults[pipeline_knobs()[k].key] = c.defaults[k];
    nlohmann::ordered_json haar = nlohmann::ordered_json::object();
    for (size_t h = 0; h < 2; ++h) {
        nlohmann::ordered_json units = nlohmann::ordered_json::object();
        for (size_t u = 0; u < kUnits; ++u) units[unit_name(Unit(u))] = unit_to_json(c.haar[h][u]);
        haar[kHaarNames[h]] = units;
    }
    return {{"provenance", c.provenance}, {"defaults", defaults}, {"haar", haar}, {"agreement", c.agreement}};
}

Calibration calibration_from_json(const nlohmann::ordered_json& j) {
    try {
        Calibration c;
        c.provenance = j.at("provenance");
        c.agreement = j.value("agreement", nlohmann::ordered_json::array());
        for (const PipelineKnob& k : pipeline_knobs()) c.defaults.push_back(j.at("defaults").at(k.key).get<double>());
        for (size_t h = 0; h < 2; ++h)
            for (size_t u = 0; u < kUnits; ++u)
                c.haar[h][u] = unit_from_json(j.at("haar").at(kHaarNames[h]).at(unit_name(Unit(u))));
        return c;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(std::string("calibration table: ") + e.what());
    }
}

std::array<double, kUnits> unit_prices(surf::HaarMode haar, const PipelineParams& params, const Calibration& c) {
    const UnitTable& table = c.haar[haar == surf::HaarMode::rounded ? 1 : 0];
    std::array<double, kUnits> prices{};
    for (size_t u = 0; u < kUnits; ++u) {
        const UnitCalibration& unit = table[u];
        double cycles = unit.cycles;
        for (size_t k = 0; k < knobs(); ++k) {
            const PipelineKnob& knob = pipeline_knobs()[k];
            const double v = params.*knob.field, d = c.defaults[k];
            if (v > d && knob.high > d) cycles += (unit.high[k] - unit.cycles) * (v - d) / (knob.high - d);
            if (v < d && knob.low < d) cycles += (unit.low[k] - unit.cycles) * (d - v) / (d - knob.low);
        }
        prices[u] = std::max(0.0, cycles);
    }
    return prices;
}

std::vector<PipelineParams> calibration_parameter_sets() {
    std::vector<PipelineParams> sets{PipelineParams{}};
    for (const PipelineKnob& k : pipeline_knobs())
        for (double v : {k.low, k.high}) {
            PipelineParams p;
            p.*k.field = v;
            sets.push_back(p);
        }
    return sets;
}

UnitTable fit_units(const std::vector<CandidateStream>& stream, const std::vector<std::array<uint64_t, kUnits>>& units) {
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
            for (size_t i = 0; i < own.size(); ++i) x(Eigen::Index(c), Eigen::Index(i)) = double(units[c][size_t(own[i])]);
        auto fit = [&](auto value, auto store) {
            std::vector<double> y;
            for (const CandidateStream& c : stream) y.push_back(value(c[s]));
            const std::vector<double> per = solve(x, y);
            for (size_t i = 0; i < own.size(); ++i) store(table[size_t(own[i])], per[i]);
        };
        fit([](const StepStream& st) { return st.cycles[0]; }, [](UnitCalibration& u, double v) { u.cycles = v; });
        // The knobs' sensitivities only from a stream timed at their probes too (the caller
        // keeps the recorded ones otherwise).
        const bool probed = !stream.empty() && stream.front()[s].cycles.size() >= 1 + 2 * knobs();
        for (size_t k = 0; probed && k < knobs(); ++k) {
            fit([&](const StepStream& st) { return st.cycles[1 + 2 * k]; }, [&](UnitCalibration& u, double v) { u.low[k] = v; });
            fit([&](const StepStream& st) { return st.cycles[2 + 2 * k]; }, [&](UnitCalibration& u, double v) { u.high[k] = v; });
        }
        fit([](const StepStream& st) { return double(st.instructions); },
            [](UnitCalibration& u, double v) { u.instructions = v; });
        for (size_t c = 0; c < kInsnClasses; ++c)
            fit([&](const StepStream& st) { return double(st.mix[c]); }, [&](UnitCalibration& u, double v) { u.mix[c] = v; });
        fit([](const StepStream& st) { return double(st.libm_calls); }, [](UnitCalibration& u, double v) { u.libm_calls = v; });
        fit([](const StepStream& st) { return double(st.libm_instructions); },
            [](UnitCalibration& u, double v) { u.libm_instructions = v; });
    }
    return table;
}

}  // namespace surfvp::sw
