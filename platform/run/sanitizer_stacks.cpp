// See sanitizer_stacks.h. libsystemc calls ASan's fiber hooks through weak references, which the
// dynamic linker binds to these definitions of the executable first; each forwards to ASan's
// own (the next definition), mending only the main stack's bounds.
#include "platform/run/sanitizer_stacks.h"

#ifdef SURFVP_ASAN
#include <cstddef>
#include <dlfcn.h>

namespace {

using StartSwitch = void (*)(void**, const void*, std::size_t);
using FinishSwitch = void (*)(void*, const void**, std::size_t*);

StartSwitch asan_start() {
    static const auto f = reinterpret_cast<StartSwitch>(dlsym(RTLD_NEXT, "__sanitizer_start_switch_fiber"));
    return f;
}
FinishSwitch asan_finish() {
    static const auto f = reinterpret_cast<FinishSwitch>(dlsym(RTLD_NEXT, "__sanitizer_finish_switch_fiber"));
    return f;
}

// The main stack as ASan knew it before the first switch: the first switch leaves it.
const void* main_bottom = nullptr;
std::size_t main_size = 0;

}  // namespace

extern "C" void __sanitizer_start_switch_fiber(void** fake_stack_save, const void* bottom, std::size_t size) {
    if (bottom == nullptr && size == 0) {  // libsystemc's way of naming the main stack
        bottom = main_bottom;
        size = main_size;
    }
    asan_start()(fake_stack_save, bottom, size);
}

extern "C" void __sanitizer_finish_switch_fiber(void* fake_stack_save, const void** bottom_old, std::size_t* size_old) {
    const void* left_bottom = nullptr;
    std::size_t left_size = 0;
    asan_finish()(fake_stack_save, &left_bottom, &left_size);
    if (main_bottom == nullptr) {
        main_bottom = left_bottom;
        main_size = left_size;
    }
    if (bottom_old) *bottom_old = left_bottom;
    if (size_old) *size_old = left_size;
}

namespace surfvp {

void back_on_main_stack() {
    if (main_bottom == nullptr) return;  // no switch yet: ASan's stack is still the main one
    void* fake_stack = nullptr;
    asan_start()(&fake_stack, main_bottom, main_size);
    asan_finish()(fake_stack, nullptr, nullptr);
}

}  // namespace surfvp
#endif
