#include "tools/spread/output_paths.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace spread::cli {

void require_output_folder(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) return;  // the working directory
  std::error_code error;
  const fs::file_status status = fs::status(folder, error);
  if (!fs::exists(status)) {
    throw std::invalid_argument(option + " " + path + ": the folder '" + folder.string() +
                                "' does not exist (create it first, e.g. mkdir -p " + folder.string() + ")");
  }
  if (!fs::is_directory(status)) {
    throw std::invalid_argument(option + " " + path + ": '" + folder.string() + "' is not a folder");
  }
}

void refuse_existing_file(const std::string& option, const std::string& path, bool overwrite,
                          const std::string& overwrite_flag) {
  std::error_code error;
  if (!overwrite && std::filesystem::exists(path, error)) {
    throw std::invalid_argument(option + " " + path + ": the file exists; choose another name, or add " +
                                overwrite_flag + " to replace it");
  }
}

}  // namespace spread::cli
