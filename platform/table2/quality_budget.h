#pragma once
// `surfvp quality-budget`: the best feature quality the chip can afford at its frame budget.
// Each combination of the CPU stage's software settings (the interpolation limit, Haar mode,
// orientation, keypoints per frame, or any axes given) is priced on the budget scenario (a
// timed run: frames/s, the CPU's time per keypoint from the calibrated PPC440 model, the frame
// rate the CPU alone would sustain) and scored on Table II sequences and a homography pair (the
// chip in direct mode: four rows of distinguishability, repeatability, precision). The report
// gives the Pareto front of quality against frames/s, names the best setting that holds the
// budget, and its gap to the best float SURF on every row, held-out sequences included. Points
// run as forked children (the sweep's engine). docs/quality_budget.md is the user's description.
#include <string>
#include <vector>

namespace surfvp {

struct QualityBudgetOptions {
    std::string budget = "budget_1024x768";  // the timed scenario with budget.fps
    std::vector<std::string> sequences;      // scored and chosen on; default castle_sequence, vtest_sequence
    std::vector<std::string> held_out;       // scored, never chosen on; default castel_sequence
    std::string pair = "graf";               // a homography pair; "none": no pair
    std::vector<std::string> axes;           // KEY=V1,V2,...; empty: the built-in software settings
    std::vector<std::string> sets;           // every scenario of the study
    std::string out;                         // default: traces/quality_budget
    unsigned jobs = 0;                       // 0: one per core
    bool quiet = false;
};

// Exit codes: 0 written, 6 some point could not run or a chip run broke (its row says why),
// 2 bad input, 3 internal error, 4 a file could not be written.
int quality_budget_command(const QualityBudgetOptions& options);

}  // namespace surfvp
