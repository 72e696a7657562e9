// PLB timing and arbitration against the formula documented in models/plb/README.md.
#include <array>
#include <memory>

#include "harness.h"
#include "models/plb/plb_bus.h"

namespace surfvp {
namespace {
using test::Initiator;
using test::ns;
using test::ZeroTarget;

struct PlbBench {
    Tracer tracer;
    PlbBus bus;
    ZeroTarget target;
    std::vector<std::unique_ptr<Initiator>> masters;

    // Several benches may share one simulation under different names.
    explicit PlbBench(const PlbBus::Params& p, const std::string& name = "bus")
        : bus(name.c_str(), p, tracer), target((name + "_target").c_str(), 1 << 20) {
        bus.slaves.bind(target.socket);
        bus.map(0x1000'0000, 1 << 20, 0, "target");
    }
    Initiator& add(const std::string& name, Initiator::Script script) {
        masters.push_back(std::make_unique<Initiator>(name.c_str(), std::move(script)));
        bus.connect_master(masters.back()->socket, name);
        return *masters.back();
    }
};

struct BurstCase {
    unsigned width_bits;
    double clock_mhz;
    unsigned beats;
};

class SingleBurst : public testing::TestWithParam<BurstCase> {};

TEST_P(SingleBurst, TakesArbitrationPlusAddressPlusBeats) {
    const BurstCase c = GetParam();
    PlbBus::Params p;
    p.width_bits = c.width_bits;
    p.clock = Frequency{c.clock_mhz * 1e6};
    p.arbitration_cycles = 3;
    p.address_cycles = 1;
    PlbBench bench(p);
    sc_core::sc_time end;
    std::vector<uint8_t> data(c.beats * c.width_bits / 8);
    bench.add("m", [&](Initiator& m) {
        EXPECT_EQ(m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'0000, data.data(), data.size()), tlm::TLM_OK_RESPONSE);
        end = m.end_time();
    });
    sc_core::sc_start();
    const double period_ns = 1e3 / c.clock_mhz;
    EXPECT_EQ(end, sc_core::sc_time((3 + 1 + c.beats) * period_ns, sc_core::SC_NS));
    EXPECT_EQ(end, bench.bus.transaction_time(data.size()));
    EXPECT_EQ(bench.bus.master_stats()[0].bytes_written, data.size());
    EXPECT_EQ(bench.bus.write_stats().busy, end);
}

INSTANTIATE_TEST_SUITE_P(WidthsClocksBeats, SingleBurst,
                         testing::Values(BurstCase{128, 100, 16}, BurstCase{128, 100, 2}, BurstCase{64, 100, 16},
                                         BurstCase{32, 125, 8}, BurstCase{128, 133.0, 16}, BurstCase{64, 200, 1}),
                         [](const testing::TestParamInfo<BurstCase>& info) {
                             return std::to_string(info.param.width_bits) + "bit_" +
                                    std::to_string(int(info.param.clock_mhz)) + "MHz_" +
                                    std::to_string(info.param.beats) + "beats";
                         });

TEST(PlbBus, LongTransactionIsSplitIntoMaxBursts) {
    PlbBus::Params p;  // 128 bit, 100 MHz, 16-beat bursts, 3 + 1 overhead
    PlbBench bench(p);
    sc_core::sc_time end;
    std::vector<uint8_t> data(40 * 16);  // 40 beats: bursts of 16, 16, 8
    bench.add("m", [&](Initiator& m) {
        m.transact(tlm::TLM_READ_COMMAND, 0x1000'0000, data.data(), data.size());
        end = m.end_time();
    });
    sc_core::sc_start();
    EXPECT_EQ(end, ns((3 * 4 + 40) * 10));
}

// Each of two masters streams four 16-beat writes from t = 0. One burst takes D = 20 cycles.
struct Contention {  // NOLINT(bugprone-reserved-identifier): clang names the array member's implicit copy loop __i0
    std::vector<sc_core::sc_time> ends[2];
};

Contention contend(PlbBus::Arbitration policy, PlbBench*& out_bench, std::unique_ptr<PlbBench>& holder) {
    PlbBus::Params p;
    p.arbitration = policy;
    holder = std::make_unique<PlbBench>(p);
    out_bench = holder.get();
    static Contention result;
    result = {};
    for (int id = 0; id < 2; ++id)
        holder->add("m" + std::to_string(id), [id](Initiator& m) {
            static uint8_t data[256];
            for (int i = 0; i < 4; ++i) {
                m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'0000 + 0x1000 * id, data, sizeof data);
                result.ends[id].push_back(m.end_time());
            }
            sc_core::wait(m.local);
        });
    sc_core::sc_start();
    return result;
}

TEST(PlbArbitration, RoundRobinAlternatesMasters) {
    std::unique_ptr<PlbBench> holder;
    PlbBench* bench = nullptr;
    const Contention c = contend(PlbBus::Arbitration::round_robin, bench, holder);
    const sc_core::sc_time D = ns(200);
    // Grants alternate m0, m1, m0, m1, ...: m0 ends at D, 3D, 5D, 7D; m1 at 2D, 4D, 6D, 8D.
    EXPECT_EQ(c.ends[0], (std::vector<sc_core::sc_time>{D, 3 * D, 5 * D, 7 * D}));
    EXPECT_EQ(c.ends[1], (std::vector<sc_core::sc_time>{2 * D, 4 * D, 6 * D, 8 * D}));
    EXPECT_EQ(bench->bus.master_stats()[0].wait, 3 * D);  // each of its last three requests waits one burst
    EXPECT_EQ(bench->bus.master_stats()[1].wait, 4 * D);
    EXPECT_EQ(bench->bus.write_stats().busy, 8 * D);
    // A burst D = 20 bus cycles at 100 MHz: m0's waits 0, D, D, D; m1's D four times.
    EXPECT_EQ(bench->bus.master_stats()[0].max_wait, D);
    EXPECT_EQ(bench->bus.master_stats()[0].wait_histogram, (std::array<uint64_t, 8>{1, 0, 0, 0, 0, 3, 0, 0}));
    EXPECT_EQ(bench->bus.master_stats()[1].wait_histogram, (std::array<uint64_t, 8>{0, 0, 0, 0, 0, 4, 0, 0}));
    EXPECT_EQ(PlbBus::wait_bin_name(5), "16-31");
}

TEST(PlbArbitration, FixedPriorityServesTheFirstMasterFirst) {
    std::unique_ptr<PlbBench> holder;
    PlbBench* bench = nullptr;
    const Contention c = contend(PlbBus::Arbitration::fixed_priority, bench, holder);
    const sc_core::sc_time D = ns(200);
    EXPECT_EQ(c.ends[0], (std::vector<sc_core::sc_time>{D, 2 * D, 3 * D, 4 * D}));
    EXPECT_EQ(c.ends[1], (std::vector<sc_core::sc_time>{5 * D, 6 * D, 7 * D, 8 * D}));
    EXPECT_EQ(bench->bus.master_stats()[0].wait, sc_core::SC_ZERO_TIME);
    EXPECT_EQ(bench->bus.master_stats()[1].wait, 4 * D);
    // m1's first burst waits all four of m0's (80 cycles), the others none.
    EXPECT_EQ(bench->bus.master_stats()[1].max_wait, 4 * D);
    EXPECT_EQ(bench->bus.master_stats()[1].wait_histogram, (std::array<uint64_t, 8>{3, 0, 0, 0, 0, 0, 0, 1}));
    EXPECT_EQ(PlbBus::wait_bin_name(7), "64+");
}

// A 4-burst write from m0 at t = 0 and a 1-burst write from m1 at 50 ns: m1 gets the bus at
// m0's first burst boundary (round robin), and m0's last three bursts follow it. m0 issues
// it as one transaction, or as one per burst.
struct Interleaving {
    explicit Interleaving(bool line_as_bursts, const std::string& name) : bench(PlbBus::Params{}, name) {
        bench.add(name + "_m0", [this, line_as_bursts](Initiator& m) {
            static uint8_t data[1024];
            const unsigned step = line_as_bursts ? 256 : 1024;
            for (unsigned done = 0; done < 1024; done += step)
                m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'0000 + done, data + done, step);
            end[0] = m.end_time();
            sc_core::wait(m.local);
        });
        bench.add(name + "_m1", [this](Initiator& m) {
            static uint8_t data[256];
            m.local = ns(50);
            m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'8000, data, sizeof data);
            end[1] = m.end_time();
            sc_core::wait(m.local);
        });
    }
    const PlbBus::MasterStats& stats(int m) const { return bench.bus.master_stats()[size_t(m)]; }

    PlbBench bench;
    sc_core::sc_time end[2];
};

TEST(PlbArbitration, ALongTransactionYieldsTheBusAtBurstBoundaries) {
    Interleaving r(false, "line");
    sc_core::sc_start();
    const sc_core::sc_time D = ns(200);
    EXPECT_EQ(r.end[1], 2 * D);  // granted at D, when m0's first burst ends
    EXPECT_EQ(r.end[0], 5 * D);
    EXPECT_EQ(r.stats(1).wait, D - ns(50));
    EXPECT_EQ(r.stats(0).wait, D);  // its second burst waited for m1's
    EXPECT_EQ(r.stats(0).bursts, 4u);
    EXPECT_EQ(r.bench.bus.write_stats().busy, 5 * D);
}

// Whether a master issues one transaction per line or per burst is a simulation setting: the
// bus gives the same figures.
TEST(PlbArbitration, OneTransactionPerLineOrPerBurstGivesTheSameFigures) {
    Interleaving line(false, "line"), bursts(true, "bursts");
    sc_core::sc_start();
    for (int m = 0; m < 2; ++m) {
        EXPECT_EQ(line.end[m], bursts.end[m]) << m;
        EXPECT_EQ(line.stats(m).wait, bursts.stats(m).wait) << m;
        EXPECT_EQ(line.stats(m).busy, bursts.stats(m).busy) << m;
        EXPECT_EQ(line.stats(m).bursts, bursts.stats(m).bursts) << m;
    }
    EXPECT_EQ(line.bench.bus.write_stats().busy, bursts.bench.bus.write_stats().busy);
    EXPECT_LT(line.bench.bus.tlm_transactions(), bursts.bench.bus.tlm_transactions());
}

TEST(PlbBus, ReadAndWriteDataPathsDoNotContend) {
    PlbBench bench(PlbBus::Params{});
    sc_core::sc_time ends[2];
    static uint8_t data[256];
    bench.add("reader", [&](Initiator& m) {
        m.transact(tlm::TLM_READ_COMMAND, 0x1000'0000, data, sizeof data);
        ends[0] = m.end_time();
    });
    bench.add("writer", [&](Initiator& m) {
        m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'1000, data, sizeof data);
        ends[1] = m.end_time();
    });
    sc_core::sc_start();
    EXPECT_EQ(ends[0], ns(200));
    EXPECT_EQ(ends[1], ns(200));
}

TEST(PlbBus, UnmappedAddressIsAnErrorResponseAndTheBusGoesOn) {
    PlbBench bench(PlbBus::Params{});
    tlm::tlm_response_status unmapped{}, straddling{}, after{};
    uint8_t data[16] = {1, 2, 3};
    bench.add("m", [&](Initiator& m) {
        unmapped = m.transact(tlm::TLM_READ_COMMAND, 0x2000'0000, data, 4);
        straddling = m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'0000 + (1 << 20) - 8, data, 16);
        after = m.transact(tlm::TLM_WRITE_COMMAND, 0x1000'0010, data, 16);
    });
    sc_core::sc_start();
    EXPECT_EQ(unmapped, tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(straddling, tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(after, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(bench.bus.decode_errors(), 2u);
    EXPECT_EQ(bench.bus.master_stats()[0].errors, 2u);
    EXPECT_EQ(bench.target.data[0x10], 1);
}

TEST(PlbBus, RejectsWidthsThePlbDoesNotHave) {
    PlbBus::Params p;
    p.width_bits = 96;
    Tracer tracer;
    EXPECT_THROW(PlbBus("bus", p, tracer), std::invalid_argument);
}

TEST(PlbBus, OverlappingRegionsAreRefused) {
    PlbBench bench(PlbBus::Params{});
    EXPECT_THROW(bench.bus.map(0x1008'0000, 0x1000, 0, "overlap"), std::invalid_argument);
}

}  // namespace
}  // namespace surfvp
