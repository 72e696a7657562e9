// The software stage as the PPC440 runs it: the same BasicSoftwareStage (sw/stage), compiled
// by powerpc-linux-gnu-g++ for the PPC440 with its FPU and run under qemu-ppc by
// `surfvp calibrate` (platform/calibrate.cpp). Its meter marks each step with a call to a
// function of its own, so that the instruction trace can be cut into steps; it counts nothing
// itself. Input and output are big-endian, as the chip's memory (calibration_dump.h).
//
//   stage_firmware INPUT OUTPUT
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "sw/cpu_cost/calibration_dump.h"
#include "sw/stage/software_stage_impl.h"

// One function per step boundary. noipa keeps each a call of its own at its own address (no
// inlining, no merging of identical bodies); the store makes the bodies differ anyway.
extern "C" {
volatile int surfvp_step = -1;
__attribute__((noinline, noipa)) void surfvp_mark_check() { surfvp_step = 0; }
__attribute__((noinline, noipa)) void surfvp_mark_interpolation() { surfvp_step = 1; }
__attribute__((noinline, noipa)) void surfvp_mark_laplacian() { surfvp_step = 2; }
__attribute__((noinline, noipa)) void surfvp_mark_orientation() { surfvp_step = 3; }
__attribute__((noinline, noipa)) void surfvp_mark_descriptor() { surfvp_step = 4; }
__attribute__((noinline, noipa)) void surfvp_mark_idle() { surfvp_step = -1; }
}

namespace {

using namespace surfvp::sw;

struct MarkingMeter {
    void enter(Step s) {
        switch (s) {
            case Step::check:
                surfvp_mark_check();
                break;
            case Step::interpolation:
                surfvp_mark_interpolation();
                break;
            case Step::laplacian:
                surfvp_mark_laplacian();
                break;
            case Step::orientation:
                surfvp_mark_orientation();
                break;
            case Step::descriptor:
                surfvp_mark_descriptor();
                break;
        }
    }
    void leave() { surfvp_mark_idle(); }
    void count(Unit, uint64_t) {}
    void load(Read, uint32_t, unsigned) {}
    void begin_frame() {}
};

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "stage_firmware: %s\n", what);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) fail("usage: stage_firmware INPUT OUTPUT");
    std::FILE* in = std::fopen(argv[1], "rb");
    std::FILE* out = std::fopen(argv[2], "wb");
    if (!in || !out) fail("cannot open the input or the output");
    calibration_dump::FrameHeader h;
    while (std::fread(&h, sizeof h, 1, in) == 1) {
        if (h.magic != calibration_dump::kMagic) fail("not a calibration dump frame");
        std::vector<uint8_t> integral(h.integral_bytes), determinants(h.determinant_bytes);
        std::vector<uint32_t> words(h.words);
        if (std::fread(integral.data(), 1, integral.size(), in) != integral.size() ||
            std::fread(determinants.data(), 1, determinants.size(), in) != determinants.size() ||
            std::fread(words.data(), 4, words.size(), in) != words.size())
            fail("truncated frame");
        BasicSoftwareStage<MarkingMeter> stage(calibration_dump::stage_params(h));
        const FrameBuffers buffers = calibration_dump::frame_buffers(h, integral.data(), determinants.data());
        for (uint32_t word : words) {
            calibration_dump::Result r{};
            if (auto kp = stage.process(word, buffers)) calibration_dump::fill(r, *kp);
            if (std::fwrite(&r, sizeof r, 1, out) != 1) fail("cannot write the output");
        }
    }
    return std::fclose(out) == 0 ? 0 : 2;
}
