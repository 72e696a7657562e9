// libsystemc.so's main() calls sc_main, so a program that links SystemC must define it. In a
// fuzz target libFuzzer's main() runs instead (the executable's own main() comes first):
// reaching this means that the wrong main() ran.
#include <cstdio>
#include <cstdlib>

extern "C" int sc_main(int, char**) {
    std::fprintf(stderr, "surfvp fuzz: SystemC's main() ran instead of libFuzzer's\n");
    std::abort();
}
