#include "describer.h"

#include "models/fhg/filter_geometry.h"
#include "models/fhg/local_max_finder.h"

namespace surfvp {
namespace {

// Until the software stage is wired: a keypoint at the candidate itself, at no cost.
class CandidateDescriber : public sw::ssa2::Describer {
public:
    std::optional<surf::Keypoint> describe(sw::Hal&, uint32_t word, const sw::ssa2::FrameInMemory&, uint64_t& cycles) override {
        const fhg::Candidate c = fhg::unpack_candidate(word);
        cycles = 0;
        surf::Keypoint k;
        k.x = float(c.x);
        k.y = float(c.y);
        k.scale = 1.2f * float(fhg::kSizes[size_t(c.size_index)]) / 9.f;
        return k;
    }
};

}  // namespace

std::unique_ptr<sw::ssa2::Describer> make_describer(const Config&, float) { return std::make_unique<CandidateDescriber>(); }

}  // namespace surfvp
