// Context: display lists (§5.4). A list holds calls as the call table describes
// them; executing it invokes each through the table, as a replayed trace does.
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <iterator>
#include <limits>
#include <map>

#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "stages/kernel_paths.hpp"

namespace passim {

void Context::glNewList(GLuint list, GLenum mode) {
  PASSIM_ENTRY(list, mode)
  if (list == 0) return set_error(GL_INVALID_VALUE);
  if (mode != GL_COMPILE && mode != GL_COMPILE_AND_EXECUTE) return set_error(GL_INVALID_ENUM);
  if (compiling_list_ != 0) return set_error(GL_INVALID_OPERATION);
  compiling_list_ = list;
  compile_mode_ = mode;
  compiling_calls_.clear();
  compiling_bytes_ = 0;
}

void Context::glEndList() {
  PASSIM_ENTRY()
  if (compiling_list_ == 0) return set_error(GL_INVALID_OPERATION);
  if (auto old = lists_.find(compiling_list_); old != lists_.end()) memory_.release(list_bytes(old->second));
  memory_.release(compiling_bytes_);  // charged while compiling; charged again below as the list's
  compiling_bytes_ = 0;
  memory_.charge(list_bytes(compiling_calls_), "a display list");  // fits: it was charged as it grew
  lists_[compiling_list_] = std::move(compiling_calls_);
  compiling_calls_.clear();
  find_triangle_batches(compiling_list_);
  compiling_list_ = 0;
  compile_mode_ = 0;
}

void Context::find_triangle_batches(GLuint list) {
  static const CallInfo* const begin = find_call("glBegin");
  static const CallInfo* const end = find_call("glEnd");
  static const CallInfo* const vertex = find_call("glVertex4d");
  static const CallInfo* const normal = find_call("glNormal3d");
  // Smaller blocks are drawn call by call (not worth a task on the lanes).
  constexpr std::size_t kMinimumTriangles = 64;
  std::vector<TriangleBatch> batches;
  const std::vector<Call>& calls = lists_[list];
  for (std::size_t i = 0; i < calls.size(); ++i) {
    if (calls[i].info != begin || calls[i].args.size() != 1 || calls[i].args[0].i != GL_TRIANGLES) continue;
    TriangleBatch b;
    b.begin_call = i;
    // Distinct by their bits (so −0 and 0, or two NaNs, stay apart when their bits differ).
    std::map<std::array<std::uint64_t, 8>, std::uint32_t> distinct;
    std::size_t j = i + 1;
    for (; j < calls.size(); ++j) {
      const Call& c = calls[j];
      if (c.info == normal && c.args.size() == 3) {
        b.last_normal = Vec3(c.args[0].d, c.args[1].d, c.args[2].d);
        b.sets_normal = true;
      } else if (c.info == vertex && c.args.size() == 4) {
        const Vec4 position(c.args[0].d, c.args[1].d, c.args[2].d, c.args[3].d);
        const Vec3 n = b.sets_normal ? b.last_normal : Vec3(0.0);
        const std::array<std::uint64_t, 8> key{
            std::bit_cast<std::uint64_t>(position.x), std::bit_cast<std::uint64_t>(position.y),
            std::bit_cast<std::uint64_t>(position.z), std::bit_cast<std::uint64_t>(position.w),
            std::bit_cast<std::uint64_t>(n.x),        std::bit_cast<std::uint64_t>(n.y),
            std::bit_cast<std::uint64_t>(n.z),        b.sets_normal ? 0u : 1u};
        const auto [at, added] = distinct.try_emplace(key, static_cast<std::uint32_t>(b.positions.size()));
        if (added) {
          b.positions.push_back(position);
          b.normals.push_back(n);
          b.inherits.push_back(b.sets_normal ? 0 : 1);
        }
        b.vertices.push_back(at->second);
      } else {
        break;
      }
    }
    if (j < calls.size() && calls[j].info == end && b.vertices.size() >= 3 * kMinimumTriangles) {
      b.end_call = j;
      batches.push_back(std::move(b));
    }
    i = j - 1;  // the call that ended the block is looked at again
  }
  if (batches.empty()) list_batches_.erase(list);
  else list_batches_[list] = std::move(batches);
}

std::uint64_t Context::list_bytes(const std::vector<Call>& calls) {
  std::uint64_t bytes = calls.capacity() * sizeof(Call);
  for (const Call& c : calls) bytes += call_bytes(c);
  return bytes;
}

std::uint64_t Context::call_bytes(const Call& call) {
  std::uint64_t bytes = call.args.capacity() * sizeof(Value);
  for (const Value& v : call.args) bytes += (v.bytes ? v.bytes->size() : 0) + (v.text ? v.text->size() : 0);
  return bytes;
}

void Context::execute_list(GLuint list) {
  auto it = lists_.find(list);
  if (it == lists_.end()) return;  // §5.4: an undefined list does nothing
  // §5.4: beyond MAX_LIST_NESTING, CallList is ignored.
  if (list_nesting_ >= profile_.limits.max_list_nesting) return;
  // Lists that call lists multiply work (a list calling another twice, 64 deep, is 2^64 calls):
  // one outermost call may execute at most kMaxListExecutions lists. Not a GL rule; a run that
  // passes it ends with a message (docs/hostile-input.md).
  if (list_nesting_ == 0) lists_executed_ = 0;
  if (++lists_executed_ > kMaxListExecutions)
    throw ClientDataError(fmt::format("display lists: one call executed more than {} lists (lists that call lists "
                                      "multiply work); passim stops here",
                                      kMaxListExecutions));
  struct Nesting {  // one level deeper while the list runs, also when it throws
    int& depth;
    explicit Nesting(int& d) : depth(++d) {}
    ~Nesting() { --depth; }
  } nesting(list_nesting_);
  // Copy-free: a list cannot be redefined while it runs (NewList is not compiled).
  const std::vector<Call>& calls = it->second;
  // Blocks of triangles drawn as a whole are a fast path; the reference runs every call.
  const auto batches = use_specialised() ? list_batches_.find(list) : list_batches_.end();
  if (batches == list_batches_.end()) {
    for (const Call& call : calls) call.info->invoke(*this, call.args);
  } else {
    std::size_t next = 0;
    for (const TriangleBatch& batch : batches->second) {
      for (; next <= batch.begin_call; ++next) calls[next].info->invoke(*this, calls[next].args);  // up to its glBegin
      draw_triangle_batch(batch, calls);
      next = batch.end_call;
    }
    for (; next < calls.size(); ++next) calls[next].info->invoke(*this, calls[next].args);
  }
}

void Context::glCallList(GLuint list) {
  PASSIM_ENTRY(list)
  execute_list(list);
}

void Context::glCallLists(GLsizei n, GLenum type, const void* lists) {
  PASSIM_ENTRY(n, type, lists)
  if (n < 0) return set_error(GL_INVALID_VALUE);
  const int size = type_size(type);
  if (size == 0 || type == GL_DOUBLE) return set_error(GL_INVALID_ENUM);
  const std::byte* p = static_cast<const std::byte*>(lists);
  for (GLsizei k = 0; k < n && p; ++k) {
    const std::byte* e = p + static_cast<std::size_t>(k) * static_cast<std::size_t>(size);
    std::int64_t offset = 0;
    switch (type) {
      case GL_BYTE: { std::int8_t x; std::memcpy(&x, e, 1); offset = x; break; }
      case GL_UNSIGNED_BYTE: { std::uint8_t x; std::memcpy(&x, e, 1); offset = x; break; }
      case GL_SHORT: { std::int16_t x; std::memcpy(&x, e, 2); offset = x; break; }
      case GL_UNSIGNED_SHORT: { std::uint16_t x; std::memcpy(&x, e, 2); offset = x; break; }
      case GL_INT: { std::int32_t x; std::memcpy(&x, e, 4); offset = x; break; }
      case GL_UNSIGNED_INT: { std::uint32_t x; std::memcpy(&x, e, 4); offset = x; break; }
      case GL_FLOAT: { float x; std::memcpy(&x, e, 4); offset = static_cast<std::int64_t>(x); break; }
      default: break;
    }
    execute_list(static_cast<GLuint>(static_cast<std::int64_t>(list_base_) + offset));
  }
}

namespace {
// The end (one past) of a run of names, in 64 bits: list + range may pass 2^32.
std::uint64_t names_end(GLuint first, std::uint64_t range) { return std::uint64_t{first} + range; }
}  // namespace

bool Context::list_name_used(GLuint name) const {
  if (lists_.count(name)) return true;
  auto it = empty_lists_.upper_bound(name);  // the first run starting after `name`
  return it != empty_lists_.begin() && std::prev(it)->second >= name;
}

GLuint Context::glGenLists(GLsizei range) {
  PASSIM_ENTRY_RET(0, range)
  if (range < 0) {
    set_error(GL_INVALID_VALUE);
    return 0;
  }
  if (range == 0) return 0;
  // §5.4: `range` contiguous empty lists, the first run of unused names. They are kept as runs
  // of names [first, last], not one list each, so a huge range costs nothing.
  std::uint64_t first = 1;
  for (;;) {
    const std::uint64_t end = first + static_cast<std::uint64_t>(range);
    if (end - 1 > std::numeric_limits<GLuint>::max()) return 0;  // no such run of names
    std::uint64_t blocker = end;  // the first used name in [first, end), if any
    auto list = lists_.lower_bound(static_cast<GLuint>(first));
    if (list != lists_.end() && list->first < blocker) blocker = list->first;
    auto run = empty_lists_.upper_bound(static_cast<GLuint>(first));
    if (run != empty_lists_.begin() && std::prev(run)->second >= first) blocker = first;
    else if (run != empty_lists_.end() && run->first < blocker) blocker = run->first;
    if (blocker == end) break;
    // Past the used name (and the run holding it).
    first = blocker + 1;
    auto holder = empty_lists_.upper_bound(static_cast<GLuint>(blocker));
    if (holder != empty_lists_.begin() && std::prev(holder)->second >= blocker)
      first = std::uint64_t{std::prev(holder)->second} + 1;
  }
  empty_lists_[static_cast<GLuint>(first)] = static_cast<GLuint>(first + static_cast<std::uint64_t>(range) - 1);
  return static_cast<GLuint>(first);
}

void Context::glDeleteLists(GLuint list, GLsizei range) {
  PASSIM_ENTRY(list, range)
  if (range < 0) return set_error(GL_INVALID_VALUE);
  if (range == 0) return;
  // Only the lists that exist are visited (not every name of the range).
  const std::uint64_t end = names_end(list, static_cast<std::uint64_t>(range));
  for (auto it = lists_.lower_bound(list); it != lists_.end() && it->first < end;) {
    memory_.release(list_bytes(it->second));
    list_batches_.erase(it->first);
    it = lists_.erase(it);
  }
  // Runs of empty names: cut [list, end) out of each run that meets it.
  std::vector<std::pair<GLuint, GLuint>> kept;
  auto it = empty_lists_.upper_bound(list);
  if (it != empty_lists_.begin()) --it;
  while (it != empty_lists_.end() && it->first < end) {
    const auto [lo, hi] = *it;
    if (hi >= list) {
      if (lo < list) kept.emplace_back(lo, list - 1);
      if (std::uint64_t{hi} >= end) kept.emplace_back(static_cast<GLuint>(end), hi);
      it = empty_lists_.erase(it);
    } else {
      ++it;
    }
  }
  for (const auto& [lo, hi] : kept) empty_lists_[lo] = hi;
}

GLboolean Context::glIsList(GLuint list) {
  PASSIM_ENTRY_RET(GL_FALSE, list)
  return list_name_used(list) ? GL_TRUE : GL_FALSE;
}

void Context::glListBase(GLuint base) {
  PASSIM_ENTRY(base)
  list_base_ = base;
}

}  // namespace passim
