// SSA IIG and SSA FHG together: a frame in memory becomes the integral image and the
// determinants in memory, and candidates in the maxima FIFO, exactly as the cores compute
// them; PixelBus back-pressure stalls the IIG when the FHG is slower.
#include <cstring>

#include "harness.h"
#include "models/common/byte_order.h"
#include "models/fhg/fhg.h"
#include "models/fhg/fhg_regs.h"
#include "models/iig/iig.h"
#include "models/iig/iig_regs.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "test_images.h"

namespace surfvp {
namespace {
using test::Initiator;
namespace r = fhg_regs;

constexpr uint32_t kIig = 0x1000, kFhg = 0x2000;  // register windows on the test's PLB1
constexpr uint32_t kImage = 0x10'0000, kIntegral = 0x40'0000, kDets = 0x80'0000;

struct PairBench {
    Tracer tracer;
    DdrMemory memory{"memory", DdrMemory::Params{}};
    PlbBus plb1{"plb1", PlbBus::Params{}, tracer};
    PlbBus plb2{"plb2", PlbBus::Params{}, tracer};
    Iig iig;
    Fhg fhg;
    sc_core::sc_signal<bool> iig_irq, fhg_irq;
    Initiator cpu;

    PairBench(const Iig::Params& ip, const Fhg::Params& fp, Initiator::Script script)
        : iig("iig", ip, tracer), fhg("fhg", fp, tracer), cpu("cpu", std::move(script)) {
        plb1.connect_master(cpu.socket, "cpu");
        plb1.slaves.bind(iig.regs);
        plb1.slaves.bind(fhg.regs);
        plb1.map(kIig, 0x100, 0, "iig");
        plb1.map(kFhg, 0x100, 1, "fhg");
        plb2.connect_master(iig.mplb, "iig");
        plb2.connect_master(fhg.mplb, "fhg");
        plb2.slaves.bind(memory.ports);
        plb2.map(0, 256u << 20, 0, "ddr");
        iig.pixels.bind(fhg.pixels);
        iig.irq.bind(iig_irq);
        fhg.irq.bind(fhg_irq);
    }
};

uint32_t pair_read(Initiator& m, uint32_t a) {
    uint8_t b[4];
    EXPECT_EQ(m.transact(tlm::TLM_READ_COMMAND, a, b, 4), tlm::TLM_OK_RESPONSE) << std::hex << a;
    sc_core::wait(m.local);
    m.local = sc_core::SC_ZERO_TIME;
    return load_be32(b);
}
void pair_write(Initiator& m, uint32_t a, uint32_t v) {
    uint8_t b[4];
    store_be32(b, v);
    EXPECT_EQ(m.transact(tlm::TLM_WRITE_COMMAND, a, b, 4), tlm::TLM_OK_RESPONSE) << std::hex << a;
    sc_core::wait(m.local);
    m.local = sc_core::SC_ZERO_TIME;
}

struct Outcome {
    std::vector<uint32_t> fifo;
    uint32_t iig_status = 0, fhg_status = 0, stall_cycles = 0, overflow = 0;
};

// The frame as the driver will run it: FHG first, then the IIG streaming into it.
Initiator::Script frame(const cv::Mat& image, int32_t threshold, Outcome& out, PairBench*& bench) {
    return [&image, threshold, &out, &bench](Initiator& m) {
        pair_write(m, kFhg + r::DET_ADDR, kDets);
        pair_write(m, kFhg + r::WIDTH, image.cols);
        pair_write(m, kFhg + r::HEIGHT, image.rows);
        pair_write(m, kFhg + r::THRESHOLD, uint32_t(threshold));
        pair_write(m, kFhg + r::CTRL, r::CTRL_START | r::CTRL_IRQ_EN_DONE);
        pair_write(m, kIig + iig::SRC, kImage);
        pair_write(m, kIig + iig::DST, kIntegral);
        pair_write(m, kIig + iig::WIDTH, image.cols);
        pair_write(m, kIig + iig::HEIGHT, image.rows);
        pair_write(m, kIig + iig::CTRL, iig::CTRL_START | iig::CTRL_IRQ_EN | iig::CTRL_STREAM);
        while (!bench->fhg_irq.read()) sc_core::wait(bench->fhg_irq.posedge_event());
        for (uint32_t word; (word = pair_read(m, kFhg + r::FIFO_DATA)) >> 31;) out.fifo.push_back(word);
        out.iig_status = pair_read(m, kIig + iig::STATUS);
        out.fhg_status = pair_read(m, kFhg + r::STATUS);
        out.stall_cycles = pair_read(m, kIig + iig::STALL_CYCLES);
        out.overflow = pair_read(m, kFhg + r::OVERFLOW_COUNT);
    };
}

void load(PairBench& bench, const cv::Mat& image) {
    uint8_t* ddr = bench.memory.backdoor(kImage, size_t(image.cols) * image.rows);
    for (int y = 0; y < image.rows; ++y) std::memcpy(ddr + size_t(y) * image.cols, image.ptr(y), image.cols);
}

TEST(IigFhg, FrameGivesTheCoresResultsInMemoryAndFifo) {
    const cv::Mat image = test::graf_1024x768()(cv::Rect(200, 100, 320, 240)).clone();
    ASSERT_FALSE(image.empty());
    Fhg::Params fp;
    fp.maxima_fifo_depth = 100000;
    Outcome out;
    PairBench* bench = nullptr;
    const fhg::HessianCore core(fp.precision);
    const int32_t threshold = core.from_float(200);
    PairBench b(Iig::Params{}, fp, frame(image, threshold, out, bench));
    bench = &b;
    load(b, image);
    sc_core::sc_start();

    EXPECT_EQ(out.iig_status, iig::STATUS_DONE);
    EXPECT_EQ(out.fhg_status, r::STATUS_DONE);
    // The integral image, bit for bit.
    const auto integral = *IntegralCore(28).image(image.data, image.cols, image.rows, image.step);
    const uint8_t* ii = b.memory.backdoor(kIntegral, integral.size() * 4);
    for (size_t i = 0; i < integral.size(); ++i) ASSERT_EQ(load_be32(ii + 4 * i), integral[i]) << i;
    // The determinants, record by record, and the candidates in FIFO order.
    const IntegralView view{integral.data(), image.cols, image.rows, size_t(image.cols)};
    const int blocks = image.cols / 2;
    std::vector<int32_t> records(size_t(blocks) * fhg::kDeterminantsPerBlock);
    std::vector<fhg::Candidate> expected;
    const uint8_t* dets = b.memory.backdoor(kDets, size_t(blocks) * (image.rows / 2) * r::record_bytes(4));
    for (int by = 0; by < image.rows / 2; ++by) {
        core.block_row(view, by, records.data());
        fhg::LocalMaxFinder(threshold).block_row(records.data(), blocks, by, expected);
        for (size_t i = 0; i < records.size(); ++i)
            ASSERT_EQ(int32_t(load_be32(dets + (size_t(by) * records.size() + i) * 4)), records[i]) << by << "/" << i;
    }
    ASSERT_GT(expected.size(), 10u);
    ASSERT_EQ(out.fifo.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(fhg::unpack_candidate(out.fifo[i]), expected[i]) << i;
    EXPECT_EQ(out.overflow, 0u);
    // Computing time is exactly blocks x block cycles at the FHG clock.
    EXPECT_EQ(b.fhg.stats().computing,
              sc_core::sc_time(double(blocks) * (image.rows / 2) * b.fhg.block_cycles() * 10, sc_core::SC_NS));
    EXPECT_EQ(b.fhg.block_cycles(), b.fhg.sequence().interval);
}

TEST(IigFhg, SlowFhgStallsTheIigThroughPixelBus) {
    const cv::Mat image = test::graf_1024x768()(cv::Rect(0, 0, 256, 160)).clone();
    ASSERT_FALSE(image.empty());
    sc_core::sc_time fast_stall, slow_stall;
    Fhg::Params slow;
    slow.clock = Frequency{10e6};
    Outcome out;
    PairBench* bench = nullptr;
    PairBench b(Iig::Params{}, slow, frame(image, 1 << 30, out, bench));
    bench = &b;
    load(b, image);
    sc_core::sc_start();
    EXPECT_EQ(out.fhg_status, r::STATUS_DONE);
    EXPECT_GT(out.stall_cycles, 10000u);
    EXPECT_GT(b.iig.stats().stalled, b.iig.stats().busy / 2) << "the IIG spends most of the frame waiting";
    EXPECT_EQ(b.fhg.stats().lines_high_water, slow.sequence.fifo_lines);
}

// At equal clocks the FHG needs ~13 cycles a pixel against the IIG's one, so here the IIG
// is made the slower: 2 MHz.
TEST(IigFhg, SlowIigNeverStalls) {
    const cv::Mat image = test::graf_1024x768()(cv::Rect(0, 0, 256, 160)).clone();
    ASSERT_FALSE(image.empty());
    Iig::Params slow;
    slow.clock = Frequency{2e6};
    const Fhg::Params fast;
    Outcome out;
    PairBench* bench = nullptr;
    PairBench b(slow, fast, frame(image, 1 << 30, out, bench));
    bench = &b;
    load(b, image);
    sc_core::sc_start();
    EXPECT_EQ(out.fhg_status, r::STATUS_DONE);
    EXPECT_EQ(out.stall_cycles, 0u);
    EXPECT_LT(b.fhg.stats().lines_high_water, fast.sequence.fifo_lines);
}

TEST(IigFhg, FullMaximaFifoCountsWhatItDrops) {
    const cv::Mat image = test::graf_1024x768()(cv::Rect(200, 100, 320, 240)).clone();
    Fhg::Params fp;
    fp.maxima_fifo_depth = 16;
    Outcome out;
    PairBench* bench = nullptr;
    PairBench b(Iig::Params{}, fp, frame(image, 0, out, bench));
    bench = &b;
    load(b, image);
    sc_core::sc_start();
    EXPECT_EQ(out.fifo.size(), 16u);
    EXPECT_GT(out.overflow, 100u);
    EXPECT_TRUE(out.fhg_status & r::STATUS_FIFO_OVERFLOW);
    EXPECT_EQ(b.fhg.stats().dropped, out.overflow);
}

TEST(IigFhg, SizeBeyondTheLimitIsAnErrorWithInterrupt) {
    uint32_t status = 0, code = 0;
    PairBench* bench = nullptr;
    PairBench b(Iig::Params{}, Fhg::Params{}, [&](Initiator& m) {
        pair_write(m, kFhg + r::WIDTH, 2048);
        pair_write(m, kFhg + r::HEIGHT, 768);
        pair_write(m, kFhg + r::CTRL, r::CTRL_START | r::CTRL_IRQ_EN_DONE);
        sc_core::wait(sc_core::sc_time(1, sc_core::SC_US));
        EXPECT_TRUE(bench->fhg_irq.read());
        status = pair_read(m, kFhg + r::STATUS);
        code = pair_read(m, kFhg + r::ERROR_CODE);
    });
    bench = &b;
    sc_core::sc_start();
    EXPECT_EQ(status, r::STATUS_ERROR);
    EXPECT_EQ(code, uint32_t(r::ERR_SIZE));
}

TEST(IigFhg, IigBusErrorAndAbortEndBothFrames) {
    uint32_t iig_status = 0, iig_code = 0, fhg_code = 0;
    PairBench* bench = nullptr;
    PairBench b(Iig::Params{}, Fhg::Params{}, [&](Initiator& m) {
        pair_write(m, kFhg + r::WIDTH, 64);
        pair_write(m, kFhg + r::HEIGHT, 64);
        pair_write(m, kFhg + r::DET_ADDR, kDets);
        pair_write(m, kFhg + r::CTRL, r::CTRL_START | r::CTRL_IRQ_EN_DONE);
        pair_write(m, kIig + iig::SRC, 0x0FFF'FF00);  // the image runs off the end of memory at row 4
        pair_write(m, kIig + iig::DST, kIntegral);
        pair_write(m, kIig + iig::WIDTH, 64);
        pair_write(m, kIig + iig::HEIGHT, 64);
        pair_write(m, kIig + iig::CTRL, iig::CTRL_START | iig::CTRL_IRQ_EN | iig::CTRL_STREAM);
        while (!bench->iig_irq.read()) sc_core::wait(bench->iig_irq.posedge_event());
        iig_status = pair_read(m, kIig + iig::STATUS);
        iig_code = pair_read(m, kIig + iig::ERROR_CODE);
        pair_write(m, kFhg + r::CTRL, r::CTRL_ABORT | r::CTRL_IRQ_EN_DONE);
        while (!bench->fhg_irq.read()) sc_core::wait(bench->fhg_irq.posedge_event());
        fhg_code = pair_read(m, kFhg + r::ERROR_CODE);
    });
    bench = &b;
    sc_core::sc_start();
    EXPECT_EQ(iig_status, iig::STATUS_ERROR);
    EXPECT_EQ(iig_code, uint32_t(iig::ERR_READ));
    EXPECT_EQ(fhg_code, uint32_t(r::ERR_ABORTED));
}

}  // namespace
}  // namespace surfvp
