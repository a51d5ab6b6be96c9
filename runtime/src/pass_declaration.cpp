// The check the frame runs on the passes' declarations before any of them
// runs: a missing input is a one-line error at construction (or at a settings
// change), not a failure in the middle of a frame.
#include "deepgi/errors.hpp"
#include "pass.hpp"

#include <fmt/format.h>

#include <map>

namespace deepgi {

std::vector<PassDeclaration> check_pass_declarations(
    const std::vector<std::unique_ptr<Pass>>& passes, const RenderSettings& settings) {
    std::vector<PassDeclaration> declarations(passes.size());
    std::map<std::string, std::string, std::less<>> writer;  // texture -> pass
    for (std::size_t i = 0; i < passes.size(); ++i) {
        const Pass* pass = passes[i].get();
        if (!pass->enabled(settings)) continue;
        const PassDeclaration& declaration = declarations[i] = pass->declaration(settings);
        for (const PassRead& read : declaration.reads) {
            if (writer.find(read.texture) == writer.end()) {
                throw GraphicsError(fmt::format(
                    "pass '{}' reads the texture '{}', which no earlier enabled pass writes",
                    pass->name(), read.texture));
            }
        }
        for (const std::string& name : declaration.writes) {
            const auto [found, inserted] = writer.emplace(name, std::string(pass->name()));
            if (!inserted) {
                throw GraphicsError(
                    fmt::format("pass '{}' writes the texture '{}', which pass '{}' already writes",
                                pass->name(), name, found->second));
            }
        }
    }
    // Values: any enabled pass may write them, before or after the reader.
    std::map<std::string, std::string, std::less<>> value_writer;  // value -> pass
    for (std::size_t i = 0; i < passes.size(); ++i) {
        const std::string_view pass = passes[i]->name();
        for (const PassValue& value : declarations[i].value_writes) {
            if (value.name.size() <= pass.size() + 1 ||
                value.name.compare(0, pass.size(), pass) != 0 || value.name[pass.size()] != '.') {
                throw GraphicsError(fmt::format(
                    "pass '{}' writes the value '{}', which is not named '{}.<setting>'", pass,
                    value.name, pass));
            }
            const auto [found, inserted] = value_writer.emplace(value.name, std::string(pass));
            if (!inserted) {
                throw GraphicsError(
                    fmt::format("pass '{}' writes the value '{}', which pass '{}' already writes",
                                pass, value.name, found->second));
            }
        }
    }
    for (std::size_t i = 0; i < passes.size(); ++i) {
        for (const std::string& name : declarations[i].value_reads) {
            if (value_writer.find(name) == value_writer.end()) {
                throw GraphicsError(
                    fmt::format("pass '{}' reads the value '{}', which no enabled pass writes",
                                passes[i]->name(), name));
            }
        }
    }
    return declarations;
}

}  // namespace deepgi
