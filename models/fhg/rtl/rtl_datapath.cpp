#include "rtl_datapath.h"

#include <Vfhg_datapath.h>
#include <fmt/format.h>
#include <unistd.h>
#include <verilated.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>

#include "models/fhg/rtl_parameters.h"
#include "models/host/atomic_file.h"

namespace surfvp::fhg {
namespace {

// fhg_params.vh as the build verilated it (generated beside the verilated model).
constexpr const char* kBuiltParameters =
#include "fhg_params_built.inc"
    ;

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// "localparam NAME = VALUE;  // ..." as {NAME, VALUE}; any other line whole as its own name.
std::pair<std::string, std::string> parameter_of(const std::string& line) {
    const size_t eq = line.find(" = "), semicolon = line.find(';');
    if (line.rfind("localparam ", 0) != 0 || eq == std::string::npos || semicolon == std::string::npos)
        return {line, ""};
    return {line.substr(11, eq - 11), line.substr(eq + 3, semicolon - eq - 3)};
}

// The image in a file the RTL's $readmemh reads at its first evaluation, removed when done.
struct ImageFile {
    std::filesystem::path path;
    explicit ImageFile(const SequenceImage& image) {
        static std::atomic<unsigned> next{0};
        path =
            std::filesystem::temp_directory_path() / fmt::format("surfvp_rtl_{}_{}.mem", ::getpid(), next.fetch_add(1));
        if (path.string().size() >= 128)  // the RTL's plusarg is a 1024-bit string
            throw std::invalid_argument("the temporary folder's path is too long for the RTL's +sequence= (" +
                                        path.string() + "): set TMPDIR to a shorter one");
        write_file_atomically(path, to_readmemh(image, "fhg.model=rtl"));
    }
    ~ImageFile() {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
    }
};

}  // namespace

std::string rtl_build_difference(const Precision& precision, const SequenceParams& sequence, unsigned line_words) {
    const std::vector<std::string> here = lines_of(rtl_parameters(precision, sequence, line_words)),
                                   built = lines_of(kBuiltParameters);
    for (size_t i = 0; i < std::max(here.size(), built.size()); ++i) {
        const std::string a = i < here.size() ? here[i] : "", b = i < built.size() ? built[i] : "";
        if (a == b) continue;
        const auto [name, value] = parameter_of(a);
        const auto [built_name, built_value] = parameter_of(b);
        if (name == built_name && !value.empty())
            return fmt::format("{} = {} here, {} in the build", name, value, built_value);
        return fmt::format("fhg_params.vh line {} is '{}' here, '{}' in the build", i + 1, a, b);
    }
    return "";
}

struct RtlDatapath::Impl {
    std::unique_ptr<VerilatedContext> context = std::make_unique<VerilatedContext>();
    std::unique_ptr<Vfhg_datapath> rtl;
    int width = 0, height = 0, interval = 0;
    unsigned det_bits = 32;  // det_value's width: sign-extended from it
    size_t taken = 0;        // integral values the FIFO has taken this frame
    uint64_t cycle = 0;
    struct Pending {
        Row row;            // its records so far and its issue cycles
        int delivered = 0;  // determinants given out
    };
    std::map<int, Pending> rows;  // the block rows begun and not yet handed over

    // One clock cycle; the PixelBus offers a value while fewer than `available` are taken.
    void tick(const IntegralView& frame, size_t available) {
        Vfhg_datapath& r = *rtl;
        const bool offer = taken < available;
        r.in_valid = offer;
        r.in_value = offer ? frame.at(int(taken % size_t(width)), int(taken / size_t(width))) : 0;
        // clk2x (a `tdp_x2` line FIFO's) rises with clk and in the middle of its cycle.
        r.clk = 0;
        r.clk2x = 1;
        r.eval();
        r.clk2x = 0;
        r.eval();
        const bool accepted = offer && r.in_ready;
        if (r.busy && !r.stalled) ++rows[r.block_y / 2].row.cycles;  // the sequence issues a word this cycle
        r.clk = 1;
        r.clk2x = 1;
        r.eval();
        r.clk2x = 0;
        r.eval();
        taken += accepted;
        ++cycle;
    }
};

RtlDatapath::RtlDatapath(const Precision& precision, const SequenceParams& sequence, unsigned line_words,
                         const SequenceImage& image)
    : impl_(std::make_unique<Impl>()) {
    const std::string difference = rtl_build_difference(precision, sequence, line_words);
    if (!difference.empty())
        throw std::invalid_argument("the verilated FHG datapath was built for the model's defaults: " + difference +
                                    " (models/fhg/rtl/README.md: re-verilate with this configuration's fhg_params.vh)");
    if (image.words.empty() || image.words.size() > kRtlSequenceDepth)
        throw std::invalid_argument(fmt::format("a sequence image of {} words: the RTL's sequence memory holds 1 to {}",
                                                image.words.size(), kRtlSequenceDepth));
    impl_->interval = int(image.words.size());
    impl_->det_bits = precision.det_bits;
    const ImageFile file(image);
    const std::string plusarg = "+sequence=" + file.path.string();
    const char* argv[] = {"surfvp", plusarg.c_str()};
    impl_->context->commandArgs(2, argv);
    impl_->rtl = std::make_unique<Vfhg_datapath>(impl_->context.get());
    impl_->rtl->eval();  // the initial blocks: $readmemh reads the image now
}

RtlDatapath::~RtlDatapath() {
    if (impl_ && impl_->rtl) impl_->rtl->final();
}

void RtlDatapath::start(int width, int height) {
    Impl& m = *impl_;
    m.width = width;
    m.height = height;
    const IntegralView none{};
    m.rtl->rst = 1;
    m.tick(none, 0);
    m.tick(none, 0);
    m.rtl->rst = 0;
    m.rtl->width = uint16_t(width);
    m.rtl->height = uint16_t(height);
    m.rtl->start = 1;
    m.tick(none, 0);
    m.rtl->start = 0;
    // The reset's cycles may have counted a word of the frame before: the frame starts here.
    m.taken = 0;
    m.cycle = 0;
    m.rows.clear();
}

RtlDatapath::Determinant RtlDatapath::step(const IntegralView& frame, size_t available) {
    Impl& m = *impl_;
    m.tick(frame, available);
    const Vfhg_datapath& r = *m.rtl;
    if (!r.det_valid) return {};
    const unsigned unused = 32 - m.det_bits;
    const int32_t value = int32_t(uint32_t(r.det_value) << unused) >> unused;
    return {true, r.det_block_x / 2, r.det_block_y / 2, int(r.det_index), value};
}

Datapath::Row RtlDatapath::row(const IntegralView& frame, int received, int by) {
    Impl& m = *impl_;
    const int blocks = (m.width + 1) / 2, wanted = blocks * kDeterminantsPerBlock;
    const size_t available = size_t(received) * size_t(m.width);
    // A row needs its sequence's cycles, the values it may still have to take and a pipeline's
    // tail; four times that and the datapath has stopped.
    const uint64_t limit = m.cycle + 4 * (uint64_t(blocks) * uint64_t(m.interval) + available + 1000);
    while (m.rows[by].delivered < wanted) {
        if (m.cycle > limit)
            throw std::runtime_error(fmt::format(
                "the verilated FHG datapath gave {} of block row {}'s {} determinants and stopped (lines received: {})",
                m.rows[by].delivered, by, wanted, received));
        const Determinant d = step(frame, available);
        if (m.rtl->overrun)
            throw std::runtime_error(fmt::format(
                "the verilated FHG datapath overran in block row {}: a TripleMAC latched a block before HessianCalc "
                "had read the one before",
                by));
        if (!d.valid) continue;
        if (d.index < 0 || d.index >= kDeterminantsPerBlock || d.block_x >= blocks)
            throw std::runtime_error(fmt::format("the verilated FHG datapath gave determinant {} of block ({}, {})",
                                                 d.index, d.block_x, d.block_y));
        Impl::Pending& pending = m.rows[d.block_y];
        pending.row.records.resize(size_t(wanted));
        pending.row.records[size_t(d.block_x) * kDeterminantsPerBlock + size_t(d.index)] = d.value;
        ++pending.delivered;
    }
    Row out = std::move(m.rows[by].row);
    m.rows.erase(by);
    return out;
}

uint64_t RtlDatapath::cycles() const { return impl_->cycle; }
bool RtlDatapath::overrun() const { return impl_->rtl->overrun; }

}  // namespace surfvp::fhg
