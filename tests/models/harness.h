#pragma once
// Small SystemC parts for model tests: a scripted initiator and a zero-time memory target.
#include <functional>
#include <gtest/gtest.h>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

namespace surfvp::test {

// Runs `script` in an SC_THREAD; transact() issues one LT transaction carrying the local
// time offset, as a temporally decoupled master does.
struct Initiator : sc_core::sc_module {
    using Script = std::function<void(Initiator&)>;
    tlm_utils::simple_initiator_socket<Initiator> socket{"socket"};
    Script script;
    sc_core::sc_time local = sc_core::SC_ZERO_TIME;

    Initiator(const sc_core::sc_module_name& name, Script s) : sc_module(name), script(std::move(s)) {
        SC_HAS_PROCESS(Initiator);
        SC_THREAD(run);
    }
    void run() { script(*this); }

    // Returns the response; `local` becomes the time at which the transaction ends,
    // relative to the kernel's time.
    tlm::tlm_response_status transact(tlm::tlm_command command, uint64_t address, uint8_t* data, unsigned bytes) {
        tlm::tlm_generic_payload tx;
        tx.set_command(command);
        tx.set_address(address);
        tx.set_data_ptr(data);
        tx.set_data_length(bytes);
        tx.set_streaming_width(bytes);
        tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
        socket->b_transport(tx, local);
        return tx.get_response_status();
    }
    sc_core::sc_time end_time() const { return sc_core::sc_time_stamp() + local; }
};

// A memory that answers at once: isolates the bus's own timing.
struct ZeroTarget : sc_core::sc_module {
    tlm_utils::simple_target_socket<ZeroTarget> socket{"socket"};
    std::vector<uint8_t> data;

    ZeroTarget(const sc_core::sc_module_name& name, size_t size) : sc_module(name), data(size) {
        socket.register_b_transport(this, &ZeroTarget::b_transport);
    }
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time&) {
        const uint64_t a = tx.get_address();
        if (a + tx.get_data_length() > data.size()) {
            tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
            return;
        }
        if (tx.is_write())
            std::copy_n(tx.get_data_ptr(), tx.get_data_length(), data.begin() + a);
        else
            std::copy_n(data.begin() + a, tx.get_data_length(), tx.get_data_ptr());
        tx.set_response_status(tlm::TLM_OK_RESPONSE);
    }
};

inline sc_core::sc_time ns(double v) { return sc_core::sc_time(v, sc_core::SC_NS); }

}  // namespace surfvp::test
