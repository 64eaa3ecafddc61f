// The table of GL entry points that traces, display lists and the recorder
// share: one row per call gives its name, argument signature and invoker, so a
// call is parsed, printed, compiled into a list and replayed by one description.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/gl.hpp"

namespace passim {

class Context;

// One argument value. Numbers keep their exact value (floats widened to double
// exactly); arrays keep the bytes the call reads, as their element type.
struct Value {
  std::int64_t i = 0;
  double d = 0.0;
  // A string argument, shared (16 bytes, not a std::string's 32: a compiled display list
  // holds millions of Values).
  std::shared_ptr<const std::string> text;
  const std::string& str() const {
    static const std::string empty;
    return text ? *text : empty;
  }
  void set_str(std::string s) { text = std::make_shared<const std::string>(std::move(s)); }
  std::shared_ptr<const std::vector<std::byte>> bytes;
  GLenum elem_type = 0;  // GL_FLOAT, GL_DOUBLE, GL_INT, GL_UNSIGNED_INT, GL_UNSIGNED_BYTE, ...
  std::size_t count = 0;  // elements
};

// Signature letters, one per parameter:
//   e enum   m primitive mode   n buffer enum (0 prints GL_NONE)   z GLboolean
//   b bitfield   i int   u uint   c GLubyte   f float   d double   s string
//   x int that may hold an enum value   y float that may hold an enum value
//   F const GLfloat*   D const GLdouble*   I const GLint*   U const GLuint*   B const GLubyte*
//   H const GLushort*
//   V const void* whose element type is the closest preceding 'e' argument
//   O output array (queries; ignored when replayed)
// An array letter is followed by its element count: a number, 'p' (by the
// preceding pname argument, see pname_count) or '*' (any length; the call checks).
struct CallInfo {
  std::string_view name;
  std::string_view signature;
  bool compiled_into_lists = true;  // §5.4: false for the calls executed immediately
  bool allowed_in_begin_end = false;  // §2.6.3
  // Changes no state the fragment stages read, so queued primitives may wait past it
  // (pipeline/raster_lanes): the calls allowed in Begin/End, Begin, the draws and Rect.
  bool keeps_raster_queue = false;
  void (*invoke)(Context&, std::span<const Value>) = nullptr;
  bool returns_value = false;
  bool query = false;            // has output arguments: never recorded or compiled
  bool recorded_at_draw = false;  // client-array pointers: recorded with their data at each draw

  // Parameter descriptions parsed from the signature.
  struct Param {
    char kind;
    char count_rule;  // 0 for scalars; 'n' fixed, 'p' by pname, '*' any
    int fixed_count;
  };
  std::vector<Param> params;
};

// nullptr when no such call is known.
const CallInfo* find_call(std::string_view name);
const std::vector<const CallInfo*>& all_calls();

// Number of values an array parameter of a *v call reads for a pname
// (glLightfv, glMaterialfv, glLightModelfv, glGet*...); 0 if the pname is unknown.
int pname_count(GLenum pname);
// Bytes of one element of a GL data type; 0 if unknown.
int type_size(GLenum type);

// The element type of array parameter `index`: its letter's (F float, D double, ...), or for
// 'V' the closest preceding enum argument's (`done` holds the arguments before it).
GLenum param_element_type(const CallInfo& info, std::size_t index, const std::vector<Value>& done);
// The fewest values array parameter `index` must hold: its fixed count, or by the pname.
std::size_t param_values_needed(const CallInfo& info, std::size_t index, const std::vector<Value>& done);

// A recorded or compiled call.
struct Call {
  const CallInfo* info = nullptr;
  std::vector<Value> args;
};

// Canonical text of a call: "glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE)".
std::string format_call(const Call& call);

}  // namespace passim

namespace passim {
// The row for a call that must exist (used by PASSIM_ENTRY; aborts on a typo).
const CallInfo& call_info_or_die(std::string_view name);
}  // namespace passim
