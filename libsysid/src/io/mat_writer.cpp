// WriteRecordingMat: a recording as a MAT v5 file (one double column vector per column), written
// through a temporary file beside the target and renamed, so a reader never sees half a file.
#include <fmt/format.h>
#include <matio.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "io/containers.hpp"
#include "io/temp_files.hpp"
#include "sysid/error.hpp"
#include "sysid/io_output.hpp"

namespace sysid {

void WriteRecordingMat(const std::string& path, const Recording& recording,
                       const std::string& description) {
  for (const auto& name : recording.names) {
    const bool ok =
        !name.empty() && name.size() <= 63 && std::isalpha(static_cast<unsigned char>(name[0])) &&
        std::all_of(name.begin(), name.end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!ok)
      throw InputError(
          fmt::format("{}: column '{}' is not a MATLAB variable name (a letter, "
                      "then letters, digits or '_', at most 63)",
                      path, name));
  }
  internal::RequireFiniteToWrite(recording, path);
  internal::WriteThroughTempFile(path, [&](int, const std::string& tmp) {
    const auto fail = [&](const std::string& why) {
      throw InputError(path + ": cannot write: " + why);
    };
    // The header names sysid (the mark a later -o looks for, sysid/io_output.hpp).
    const std::string header =
        ("MATLAB 5.0 MAT-file, " + (description.empty() ? GeneratorName() : description))
            .substr(0, 116);
    mat_t* mat = Mat_CreateVer(tmp.c_str(), header.c_str(), MAT_FT_MAT5);
    if (!mat) fail("matio cannot create the file");
    Eigen::VectorXd column;
    for (size_t c = 0; c < recording.names.size(); ++c) {
      column = recording.data.col(static_cast<Eigen::Index>(c));
      size_t dims[2] = {static_cast<size_t>(column.size()), 1};
      matvar_t* v = Mat_VarCreate(recording.names[c].c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                                  column.data(), MAT_F_DONT_COPY_DATA);
      const bool ok = v && Mat_VarWrite(mat, v, MAT_COMPRESSION_ZLIB) == 0;
      if (v) Mat_VarFree(v);
      if (!ok) {
        Mat_Close(mat);
        fail("matio cannot write variable '" + recording.names[c] + "'");
      }
    }
    if (Mat_Close(mat) != 0) fail("matio cannot close the file");
  });
}

void WriteRecordingByExtension(const std::string& path, const Recording& recording) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".mat")
    WriteRecordingMat(path, recording);
  else
    WriteRecording(path, recording);
}

}  // namespace sysid
