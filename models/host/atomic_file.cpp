#include "atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace surfvp {

void write_file_atomically(const std::filesystem::path& file, const std::string& content) {
    // pid and a counter keep concurrent writers (threads or processes) off each other's
    // temporary; the rename is atomic within one file system.
    static std::atomic<unsigned> serial{0};
    std::filesystem::path temporary = file;
    temporary += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(serial++);
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw EnvironmentError(file.string() + ": cannot create temporary " + temporary.string() + " (" +
                                   std::strerror(errno) + ")");
        }
        out.write(content.data(), static_cast<std::streamsize>(content.size()));
        out.close();
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw EnvironmentError(file.string() + ": write failed (" + std::strerror(errno) + ")");
        }
    }
    std::error_code ec;
    std::filesystem::rename(temporary, file, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw EnvironmentError(file.string() + ": cannot rename temporary into place (" + ec.message() + ")");
    }
}

}  // namespace surfvp
