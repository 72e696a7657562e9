#include "models/host/yaml_text.h"

#include <algorithm>
#include <sstream>
#include <yaml-cpp/eventhandler.h>

namespace surfvp {

namespace {

// Past a node's properties (tags "!t", "!!str", "!<x>" and anchors "&a") and the blanks after
// them: where the node's content begins in `line`.
std::size_t past_properties(const std::string& line, std::size_t at) {
    while (at < line.size() && (line[at] == '!' || line[at] == '&')) {
        at = line.find_first_of(" \t,", at);
        if (at == std::string::npos) return line.size();
        at = line.find_first_not_of(" \t", at);
        if (at == std::string::npos) return line.size();
    }
    return at;
}

}  // namespace

std::size_t yaml_hang_line(const std::string& text) {
    // yaml-cpp skips a byte-order mark and breaks lines at \n, \r\n and a lone \r.
    const std::size_t bom = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    bool document_started = false;  // a token of the current document has been seen
    std::size_t number = 0;
    for (std::size_t at = bom; at <= text.size();) {
        std::size_t end = text.find_first_of("\r\n", at);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(at, end - at);
        at = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
        ++number;
        std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        if (!document_started && line[first] == '%') continue;  // a directive
        if (line.compare(0, 3, "---") == 0 || line.compare(0, 3, "...") == 0) {
            document_started = false;
            first = line.find_first_not_of(" \t", 3);  // "--- ,": the document's first token
            if (first == std::string::npos || line[first] == '#') continue;
        }
        if (!document_started || first == 0) {
            const std::size_t content = past_properties(line, first);
            if (content < line.size() && line[content] == ',') return number;
        }
        document_started = true;
    }
    return 0;
}

namespace {

// yaml-cpp's parse of `text` as events, counted. On text it would never finish it starts one
// empty document after another without consuming a token (memory grows until it runs out):
// the ','s yaml_hang_line finds, a ',' after a complete top-level node ('"a",', '[a],', found
// by tests/fuzz sweep_file), and whatever else leads it there. A document, collection, scalar
// or alias takes at least one byte of text, so ten events a byte is a bound no text that
// yaml-cpp finishes reaches; past it, the parse is stopped where the repeating began.
class EventBound : public YAML::EventHandler {
public:
    explicit EventBound(std::size_t limit) : limit_(limit) {}
    void OnDocumentStart(const YAML::Mark& mark) override { tick(mark); }
    void OnDocumentEnd() override { tick(mark_); }
    void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { tick(mark); }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { tick(mark); }
    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
        tick(mark);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {
        tick(mark);
    }
    void OnSequenceEnd() override { tick(mark_); }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
        tick(mark);
    }
    void OnMapEnd() override { tick(mark_); }

private:
    void tick(const YAML::Mark& mark) {
        mark_ = mark;
        if (++events_ > limit_)
            throw YAML::ParserException(mark,
                                        "yaml-cpp would never finish this text: it repeats an empty document here "
                                        "without end (a ',' after a complete top-level node?)");
    }
    std::size_t limit_, events_ = 0;
    YAML::Mark mark_;
};

void refuse_endless(const std::string& text) {
    std::istringstream in(text);
    YAML::Parser parser(in);
    EventBound bound(10 * text.size() + 100);
    while (parser.HandleNextDocument(bound)) {}
}

void refuse_hang(const std::string& text) {
    if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {  // yaml-cpp loops on one
        YAML::Mark mark;
        mark.line = int(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'));
        throw YAML::ParserException(mark, "a NUL byte (YAML text holds none)");
    }
    if (const std::size_t line = yaml_hang_line(text)) {
        YAML::Mark mark;
        mark.line = int(line - 1);
        throw YAML::ParserException(mark, "a ',' where a node begins (',' only separates the entries of [ ] or { })");
    }
    refuse_endless(text);
}

}  // namespace

std::vector<YAML::Node> load_all_yaml(const std::string& text) {
    refuse_hang(text);
    return YAML::LoadAll(text);
}

YAML::Node load_yaml(const std::string& text) {
    refuse_hang(text);
    return YAML::Load(text);
}

}  // namespace surfvp
