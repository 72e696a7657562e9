#pragma once
// AddressSanitizer and SystemC's coroutines, reconciled (sanitizer builds only; elsewhere this
// is nothing).
//
// Debian's libsystemc (QuickThreads) tells ASan of each switch between coroutine stacks, but
// twice it leaves ASan with the wrong stack: a switch back to the main stack is announced with
// bottom 0 and size 0, and a switch out of a thread that ends (QuickThreads' abort) is not
// announced at all. Either way ASan then takes the main stack for a coroutine's, ignores the
// next throw's request to clear the stack's redzones ("ASan is ignoring requested
// __asan_handle_no_return") and reports false stack errors in the destructors that unwind.
// sanitizer_stacks.cpp announces the main stack's real bounds in the first case;
// back_on_main_stack() puts them back after the second. Written for GCC's ASan runtime, a
// shared library that the hooks forward to; untried with clang's, which is linked statically.
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define SURFVP_ASAN 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define SURFVP_ASAN 1
#endif
#endif

namespace surfvp {

#ifdef SURFVP_ASAN
// Call on the main stack after sc_start() returns: ASan's stack is the main stack again.
void back_on_main_stack();
#else
inline void back_on_main_stack() {}
#endif

}  // namespace surfvp
