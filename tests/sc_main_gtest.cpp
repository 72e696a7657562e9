// Test suites that link SystemC: libsystemc's main() calls sc_main, which runs GoogleTest.
// ctest runs each case in its own process, so each may elaborate and run one simulation.
#include <cstdlib>
#include <gtest/gtest.h>
#include <systemc>

int sc_main(int argc, char** argv) {
    sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
    testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
