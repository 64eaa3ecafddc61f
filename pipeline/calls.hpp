// The table of GL entry points that traces, display lists and the recorder
// share: one row per call gives its name, argument signature and invoker, so a
// call is parsed, printed, compiled into a list and replayed by one description.
#pragma once
#include <array>
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

// A row's signature names each parameter as the spec's prototype does, with a letter for
// its kind: "e:target i:level x:internalformat i:width e:format e:type V{image width}:pixels".
// Scalars:
//   e enum   m primitive mode   n buffer enum (0 prints GL_NONE)   z GLboolean
//   b bitfield (PushAttrib's and Clear's bits)   k client attribute bitfield (PushClientAttrib's)
//   i int   u uint   c GLubyte   g GLbyte   h GLshort   w GLushort
//   f float   d double   s string
//   x int that may hold an enum value   y float that may hold an enum value
// Arrays (client memory), followed by their length rule:
//   F const GLfloat*   D const GLdouble*   I const GLint*   U const GLuint*   B const GLubyte*
//   G const GLbyte*   S const GLshort*   H const GLushort*
//   V const void* whose element type is the argument named `type`
//   O output (queries write it)
// Length rules:
//   16               that many elements
//   p                as many as the argument named `pname` takes (pname_count)
//   [count]          as many as the argument named `count` says
//   {image w h d}    the bytes an image of those dimension arguments (1 when left out), with
//                    the arguments `format` and `type`, reads under the pixel-store modes (§3.6.4)
//   {bitmap w h}     the bytes of a bitmap of those dimensions (§3.6.4, type BITMAP)
//   *                not known at the call (client-array pointers: read at each draw)
//   {state}          (outputs) what the GL's state says the call writes: a texture level's
//                    image, a colour table, a filter, the histogram's or minmax's values. The
//                    row's `state_elements` computes it.
enum class Length : std::uint8_t { None, Fixed, ByPname, ByArgument, Image, Bitmap, Any, State };

struct CallInfo {
  std::string_view name;
  std::string_view signature;
  bool compiled_into_lists = true;    // §5.4: false for the calls executed immediately
  bool allowed_in_begin_end = false;  // §2.6.3
  // Changes no state the fragment stages read, so queued primitives may wait past it
  // (pipeline/raster_lanes): the calls allowed in Begin/End, Begin, the array draws and Rect.
  bool keeps_raster_queue = false;
  // Draws (primitives, pixels, clears, accumulation): what apitrace's "draw" call set selects.
  bool draws = false;
  // Reads the enabled client arrays (§2.8: ArrayElement, DrawArrays, DrawElements): recorded
  // with the array data it reads, compiled into lists as that data (§5.4). Its elements are
  // its `i`, or `first` and `count`, or `count` `indices`.
  bool reads_client_arrays = false;
  void (*invoke)(Context&, std::span<const Value>) = nullptr;
  bool returns_value = false;
  bool query = false;  // has output arguments: never compiled (§5.4); recorded with {} for them
  // Client-array pointer calls: the array they set (recorded with its data at each draw;
  // InterleavedArrays sets several, its row says GL_VERTEX_ARRAY); 0 for others.
  GLenum client_array = 0;
  bool recorded_at_draw() const { return client_array != 0; }
  // For {state} outputs: the elements output parameter `param` receives, from the context's
  // state and the arguments before it.
  std::uint64_t (*state_elements)(const Context&, std::span<const Value>, std::size_t param) = nullptr;
  bool has_outputs() const;

  struct Param {
    char kind = 0;
    std::string_view name;
    Length length = Length::None;
    int fixed_count = 0;
    int count_arg = -1;                  // ByArgument: the count; ByPname: the pname
    std::array<int, 3> dims{-1, -1, -1};  // Image, Bitmap: width, height, depth arguments (-1: 1)
    int format_arg = -1, type_arg = -1;  // Image: the format; V and Image: the type
    bool is_array() const { return length != Length::None; }
  };
  std::vector<Param> params;
  // The index of the parameter with this name; -1 when there is none.
  int param_index(std::string_view name) const;
};

// What a call run from a trace returned and wrote into its output arguments (queries, and
// glGenTextures): run_collecting() fills it.
struct CallOutput {
  std::size_t param = 0;
  GLenum type = 0;  // the element type written (GL_INT, GL_FLOAT, ... or the `type` argument's)
  std::uint64_t elements = 0;
  std::vector<std::byte> bytes;  // room for `elements` of the widest type the call may write
};
struct CallResults {
  bool returned = false;
  Value value;  // the return value: `i`, or `text` for glGetString
  std::vector<CallOutput> outputs;
};
// Runs a row's entry point with its output arguments written into `results.outputs` (one per
// output parameter, in order, sized by the caller from the row's length rules) and its return
// value kept.
void run_collecting(const CallInfo& info, Context& ctx, std::span<const Value> args, CallResults& results);

// nullptr when no such call is known.
const CallInfo* find_call(std::string_view name);
const std::vector<const CallInfo*>& all_calls();

// The values an integer scalar parameter's type holds (kinds e m n b x z i u c g h w): a reader
// refuses a trace's value outside them rather than let the conversion to the C type wrap it.
struct IntegerRange {
  std::int64_t lo = 0, hi = 0;
};
IntegerRange integer_range(char kind);

// Number of values an array parameter of a *v call reads for a pname
// (glLightfv, glMaterialfv, glLightModelfv, glGet*...); 0 if the pname is unknown.
int pname_count(GLenum pname);
// Bytes of one element of a GL data type; 0 if unknown.
int type_size(GLenum type);

struct PixelStore;
// The element type of array parameter `index`: its letter's (F float, D double, ...), or for
// 'V' the `type` argument's (`done` holds the arguments before it).
GLenum param_element_type(const CallInfo& info, std::size_t index, const std::vector<Value>& done);
// The elements array parameter `index` reads by its length rule, given the arguments before it
// and the pixel-store modes it reads under; 0 for Any, or for an image or bitmap the GL rejects
// before reading (bad format, type or size). Checked 64-bit arithmetic: SizeOverflow.
std::uint64_t param_elements_needed(const CallInfo& info, std::size_t index, const std::vector<Value>& done,
                                    const PixelStore& store);
// The elements output parameter `index` receives, images under the
// context's pack modes, {state} outputs from its state. Checked arithmetic: SizeOverflow.
std::uint64_t output_elements_needed(const CallInfo& info, std::size_t index, const std::vector<Value>& done,
                                     const Context& ctx);
// Whether a null pointer is valid for the parameter (an image or bitmap: no data).
bool param_may_be_null(const CallInfo::Param& p);

// A recorded or compiled call.
struct Call {
  const CallInfo* info = nullptr;
  std::vector<Value> args;
};

// A row as a prototype with its argument types, length rules and flags (passim info --calls):
// "glBitmap(GLint width, ..., const GLubyte* bitmap[bitmap widthxheight])  [draws]".
std::string describe_call(const CallInfo& info);

// Canonical text of a call: "glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE)".
std::string format_call(const Call& call);

}  // namespace passim

namespace passim {
// The row for a call that must exist (used by PASSIM_ENTRY; aborts on a typo).
const CallInfo& call_info_or_die(std::string_view name);
}  // namespace passim
