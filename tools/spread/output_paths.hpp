#pragma once
// Checks on the files a command will write, made before any work: a folder that does not exist is named
// at once (not after a fit of several seconds, as a library's "cannot write" message), and a file the
// technician already has is not replaced unless asked.
#include <string>

namespace spread::cli {

// The folder `path` would be written into (for a --plot PREFIX, the folder of the prefix) exists and
// is a folder. Throws std::invalid_argument naming `option`, the path and the folder.
void require_output_folder(const std::string& option, const std::string& path);

// `path` does not exist yet, or `overwrite` is set. Throws std::invalid_argument naming `option` and the
// flag that allows it.
void refuse_existing_file(const std::string& option, const std::string& path, bool overwrite,
                          const std::string& overwrite_flag);

}  // namespace spread::cli
