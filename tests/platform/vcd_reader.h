#pragma once
// A small VCD reader for tests: signal names (scopes joined by '.') and their value changes.
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace surfvp::test {

struct Vcd {
    std::string timescale;
    std::map<std::string, std::vector<std::pair<uint64_t, std::string>>> changes;  // name -> (time, value)

    static Vcd read(const std::string& path) {
        Vcd vcd;
        std::ifstream in(path);
        std::map<std::string, std::string> names;  // id -> name
        std::vector<std::string> scope;
        std::string word;
        uint64_t now = 0;
        while (in >> word) {
            if (word == "$scope") {
                std::string kind, name;
                in >> kind >> name;
                scope.push_back(name);
            } else if (word == "$upscope") {
                scope.pop_back();
            } else if (word == "$var") {
                std::string type, width, id, name;
                in >> type >> width >> id >> name;
                std::string full;
                for (size_t i = 1; i < scope.size(); ++i) full += scope[i] + ".";  // skip the top "SystemC"
                names[id] = full + name;
                vcd.changes[full + name];
            } else if (word == "$timescale") {
                std::string part;
                while (in >> part && part != "$end") vcd.timescale += part;
            } else if (word[0] == '#') {
                now = std::stoull(word.substr(1));
            } else if ((word[0] == '0' || word[0] == '1') && names.count(word.substr(1))) {
                vcd.changes[names[word.substr(1)]].push_back({now, word.substr(0, 1)});
            } else if (word[0] == 'b') {
                std::string id;
                in >> id;
                if (names.count(id)) vcd.changes[names[id]].push_back({now, word.substr(1)});
            }
        }
        return vcd;
    }

    size_t rises(const std::string& name) const {
        size_t n = 0;
        for (const auto& [t, v] : changes.at(name)) n += v == "1";
        return n;
    }
};

}  // namespace surfvp::test
