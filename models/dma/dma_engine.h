#pragma once
// The simple DMA each IP block embeds (paper §III-A): it moves a buffer over the block's
// MPLB port as a sequence of bursts, one TLM transaction per burst, and stops at the first
// error response. It spends no time of its own beyond the bus transactions; it is called
// from the owner's SC_THREAD, keeps the time of its bursts as a local offset (the bus
// synchronises at each request), and waits out the last one before returning.
#include <cstdint>
#include <systemc>
#include <tlm>

namespace surfvp {

class DmaEngine {
public:
    struct Result {
        bool ok = true;
        uint64_t failed_address = 0;  // the start of the transaction that failed
        tlm::tlm_response_status status = tlm::TLM_OK_RESPONSE;
    };

    // `port` is the owner's MPLB initiator socket; `burst_bytes` = burst beats x bus width.
    DmaEngine(tlm::tlm_initiator_socket<>& port, unsigned burst_bytes, uint64_t transaction_bytes = 0);

    Result read(uint64_t address, uint8_t* data, uint64_t bytes);
    Result write(uint64_t address, const uint8_t* data, uint64_t bytes);

    unsigned burst_bytes() const { return burst_bytes_; }
    uint64_t transactions() const { return transactions_; }

private:
    Result transfer(tlm::tlm_command command, uint64_t address, uint8_t* data, uint64_t bytes);

    tlm::tlm_initiator_socket<>& port_;
    unsigned burst_bytes_;
    uint64_t transaction_bytes_;
    uint64_t transactions_ = 0;
};

}  // namespace surfvp
