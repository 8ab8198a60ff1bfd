// libFuzzer: the Python module's keyword arguments (cli/keyword_arguments.h) as bytes decode
// them: any names and values, through the conversion to render's flags and the camera flags'
// own parser and checks. Only lfcam::Error (a UsageError) may come out.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "lfcam/cli/camera_flags.h"
#include "lfcam/cli/keyword_arguments.h"
#include "lfcam/core/error.h"

namespace {

struct Reader {
  const std::uint8_t* data;
  std::size_t size;
  std::uint8_t Byte() {
    if (size == 0) return 0;
    --size;
    return *data++;
  }
  std::string Text() {
    std::string s;
    for (std::size_t n = Byte() % 24; n > 0 && size > 0; --n) s.push_back(char(Byte()));
    return s;
  }
  double Number() {
    double x = 0;
    std::uint8_t b[sizeof x] = {};
    for (auto& v : b) v = Byte();
    std::memcpy(&x, b, sizeof x);
    return x;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in{data, size};
  const lfcam::cli::KeywordTable& table = lfcam::cli::RenderKeywordTable();
  const std::vector<std::string> known = table.names();
  std::vector<lfcam::cli::KeywordArgument> arguments;
  for (int k = in.Byte() % 6; k > 0 && in.size > 0; --k) {
    const std::uint8_t pick = in.Byte();
    std::string name = pick < 200 ? known[pick % known.size()] : in.Text();
    lfcam::cli::KeywordValue value;
    switch (in.Byte() % 5) {
      case 0:
        value = bool(in.Byte() & 1);
        break;
      case 1: {
        long long n = 0;
        const double bits = in.Number();
        std::memcpy(&n, &bits, sizeof n);
        value = n;
        break;
      }
      case 2:
        value = in.Number();
        break;
      case 3:
        value = in.Text();
        break;
      default: {
        std::vector<double> numbers(in.Byte() % 5);
        for (double& x : numbers) x = in.Number();
        value = numbers;
      }
    }
    arguments.push_back({name, value});
  }
  try {
    const std::vector<std::string> args = lfcam::cli::FlagArguments(table, arguments);
    lfcam::cli::ParseCameraFlags(args, /*rig_cameras=*/true, /*sweeps=*/false,
                                 /*allow_extras=*/true)
        ->flags.Validate();
  } catch (const lfcam::Error&) {
  }
  return 0;
}
