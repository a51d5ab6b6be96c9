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
    return declarations;
}

}  // namespace deepgi
