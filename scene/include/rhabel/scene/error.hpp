// rhabel/scene/error.hpp: the one error of the scene layer, and the rule that keeps its messages on
// one line.
//
// Every refusal of a scene (syntax, type, range, missing or unknown field, a file that cannot be
// read, a scene the solver rejects) is an input_error whose message is ONE line naming the field
// as a path (`indentors[0].radius`), the offending value and the valid range, prefixed by the
// command it came from (`solve: `, `sweep: `). The command line prints it as `rhabel: <message>`
// with exit code 2; the Python package raises it as ValueError.
#pragma once

#include <rhabel/materials/text_file.hpp>

#include <stdexcept>
#include <string>
#include <string_view>

namespace rhabel::scene {

/// Bad input: a scene (or a file it names) that is refused, with a one-line message.
struct input_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An output (stdout, a file) could not be written completely: one line naming it.
struct write_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// `text` on one line: control characters (bytes 0x00-0x1f and 0x7f) become \n, \r, \t or \xHH,
/// so that an echoed value (an argument, a file name, a JSON excerpt) cannot break the message.
inline std::string one_line(std::string_view text) { return materials::printable(text, text.size()); }

}  // namespace rhabel::scene
