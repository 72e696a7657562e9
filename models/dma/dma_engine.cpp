#include "dma_engine.h"

#include <algorithm>
#include <stdexcept>

namespace surfvp {

DmaEngine::DmaEngine(tlm::tlm_initiator_socket<>& port, unsigned burst_bytes, uint64_t transaction_bytes)
    : port_(port), burst_bytes_(burst_bytes), transaction_bytes_(transaction_bytes) {
    if (burst_bytes == 0) throw std::invalid_argument("DMA burst length must be above zero");
}

DmaEngine::Result DmaEngine::read(uint64_t address, uint8_t* data, uint64_t bytes) {
    return transfer(tlm::TLM_READ_COMMAND, address, data, bytes);
}

DmaEngine::Result DmaEngine::write(uint64_t address, const uint8_t* data, uint64_t bytes) {
    // TLM payloads carry a non-const pointer; a write command never writes through it.
    return transfer(tlm::TLM_WRITE_COMMAND, address, const_cast<uint8_t*>(data), bytes);
}

DmaEngine::Result DmaEngine::transfer(tlm::tlm_command command, uint64_t address, uint8_t* data, uint64_t bytes) {
    Result result;
    tlm::tlm_generic_payload tx;
    sc_core::sc_time local = sc_core::SC_ZERO_TIME;
    const uint64_t chunk = transaction_bytes_ ? std::max<uint64_t>(transaction_bytes_, burst_bytes_) : bytes;
    for (uint64_t done = 0; done < bytes;) {
        const auto length = static_cast<unsigned>(std::min<uint64_t>(chunk, bytes - done));
        tx.set_command(command);
        tx.set_address(address + done);
        tx.set_data_ptr(data + done);
        tx.set_data_length(length);
        tx.set_streaming_width(length);
        tx.set_byte_enable_ptr(nullptr);
        tx.set_dmi_allowed(false);
        tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
        port_->b_transport(tx, local);
        ++transactions_;
        if (!tx.is_response_ok()) {
            result = {false, address + done, tx.get_response_status()};  // the transaction that failed
            break;
        }
        done += length;
    }
    sc_core::wait(local);
    return result;
}

}  // namespace surfvp
