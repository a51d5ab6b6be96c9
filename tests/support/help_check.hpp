// Reads a CLI11 --help text the way a user does: one entry per option, and
// asks of each that it says its default (or that it is required) and that no
// parser notation leaks into it.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace spiral::test {

struct HelpEntry {
    std::string name;  // the option's first name, e.g. "--size"
    std::string text;  // its whole entry, continuation lines joined
};

// An entry starts on a line indented by two spaces and beginning with '-';
// deeper-indented lines continue it; anything else ends it.
inline std::vector<HelpEntry> help_entries(const std::string& help) {
    std::vector<HelpEntry> entries;
    std::istringstream lines(help);
    std::string line;
    bool open = false;
    while (std::getline(lines, line)) {
        // "  --size ..." or "  -h,--help"; not a key list line such as "  -   exposure".
        if (line.rfind("  -", 0) == 0 && line.size() > 3 && line[3] != ' ') {
            HelpEntry entry;
            const std::size_t end = line.find_first_of(" ,", 2);
            entry.name = line.substr(2, end == std::string::npos ? std::string::npos : end - 2);
            entry.text = line;
            entries.push_back(entry);
            open = true;
        } else if (open && line.rfind("      ", 0) == 0) {
            entries.back().text += " " + line;
        } else {
            open = false;
        }
    }
    return entries;
}

// CLI11's Range validator text, "[1 - 1099511627776]" (the help's own limits
// read "[0, 1]").
inline bool range_notation(const std::string& text) {
    for (std::size_t open = text.find('['); open != std::string::npos;
         open = text.find('[', open + 1)) {
        const std::size_t close = text.find(']', open);
        if (close != std::string::npos &&
            text.substr(open, close - open).find(" - ") != std::string::npos)
            return true;
    }
    return false;
}

// The options whose entry names no default, or shows parser notation.
inline std::vector<std::string> undocumented_options(const std::string& help) {
    std::vector<std::string> bad;
    for (const HelpEntry& entry : help_entries(help)) {
        if (entry.name == "-h") continue;  // --help itself
        const bool says_default = entry.text.find("(default: ") != std::string::npos ||
                                  entry.text.find("(required)") != std::string::npos;
        const bool parser_text = entry.text.find("{false}") != std::string::npos ||
                                 entry.text.find("{true}") != std::string::npos ||
                                 entry.text.find("UINT") != std::string::npos ||
                                 range_notation(entry.text) ||
                                 entry.text.find(":PATH") != std::string::npos;
        if (!says_default || parser_text) bad.push_back(entry.text);
    }
    return bad;
}

}  // namespace spiral::test
