#include "models/host/xml_text.h"

namespace surfvp {

std::string xml_escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            // XML 1.0 has no way to write the other control characters, not even as &#1;: each
            // becomes U+FFFD, so that a file name holding one still gives a well-formed page.
            case '\t':
            case '\n':
            case '\r':
                out += c;
                break;
            default:
                out += (unsigned char)c < 0x20 ? "\xEF\xBF\xBD" : std::string(1, c);
        }
    }
    return out;
}

}  // namespace surfvp
