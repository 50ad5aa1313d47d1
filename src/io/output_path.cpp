#include "io/output_path.h"

#include "io/output_location.h"
#include "soundpaint/result.h"

namespace sp {

bool names_stdout(const std::filesystem::path& path) { return path == "-"; }

OutputTarget resolve_output(const std::filesystem::path& path) {
  OutputLocation location = locate_output(path);
  return OutputTarget{location.to_stdout, std::move(location.file)};
}

void check_distinct_outputs(std::span<const NamedOutput> outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      OutputTarget a;
      OutputTarget b;
      try {
        a = resolve_output(outputs[j].path);
        b = resolve_output(outputs[i].path);
      } catch (const Exception&) {
        continue;  // the writer reports it, naming its own option's path
      }
      if (a.to_stdout == b.to_stdout && a.file == b.file) {
        throw Exception(ErrorCode::InvalidArgument, "options " + outputs[j].option + " and " + outputs[i].option +
                                                        " name the same output " + outputs[i].path.string());
      }
    }
  }
}

}  // namespace sp
