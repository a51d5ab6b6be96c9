// codegen's output functions: thin names over the shared atomic writer
// (fileio/), so spiralgen and deepgi follow one set of rules for output paths.
#include <spiral/codegen.hpp>
#include <spiral/fileio.hpp>

namespace spiral::codegen {

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
    fileio::write_file_atomically(path, contents);
}

void write_stdout(std::string_view contents) {
    fileio::write_file_atomically("-", contents);
}

}  // namespace spiral::codegen
