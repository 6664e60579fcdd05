// Small helpers over the HDF5 C API for the results archive (private to src/experiment).
//
// Every identifier is owned by a Handle; every failing call becomes an ArchiveError naming the
// file and the object. HDF5's serial build is not thread-safe: use these from one thread.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gjklab/experiment/archive/archive.hpp"

namespace gjklab::experiment::h5 {

/// Owns one HDF5 identifier and releases it with the matching close function (H5Fclose,
/// H5Dclose, ...). Move-only.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);

  Handle() = default;
  Handle(hid_t id, Closer closer) noexcept : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { close(); }

  hid_t get() const noexcept { return id_; }
  explicit operator bool() const noexcept { return id_ >= 0; }
  /// Releases the identifier now; returns the close function's status (0 when empty).
  herr_t close() noexcept;

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// Turns off HDF5's automatic printing of its error stack (errors become exceptions instead).
void quiet_errors();

/// The file being written or read: names it in every error message.
class Context {
 public:
  explicit Context(std::string file) : file_(std::move(file)) {}
  const std::string& file() const noexcept { return file_; }

  /// Throws ArchiveError "archive FILE: WHAT" followed by HDF5's most specific message, if any.
  [[noreturn]] void fail(std::string_view what) const;
  /// Throws ArchiveError "archive FILE: WHAT" without consulting HDF5's error stack.
  [[noreturn]] void error(std::string_view what) const;

  /// Reading an interrupted archive: datasets may hold more rows than were committed (a
  /// write cut off after the last checkpoint); open_dataset then reads only the first
  /// expected_rows rows instead of failing.
  void allow_prefix_reads(bool allow) { prefix_reads_ = allow; }
  bool prefix_reads() const { return prefix_reads_; }

  /// Returns id when it is valid, else fail(what).
  hid_t check_id(hid_t id, std::string_view what) const {
    if (id < 0) fail(what);
    return id;
  }
  void check(herr_t status, std::string_view what) const {
    if (status < 0) fail(what);
  }
  /// check(htri_t): true, false, or fail(what).
  bool check_tri(htri_t value, std::string_view what) const {
    if (value < 0) fail(what);
    return value > 0;
  }
  Handle handle(hid_t id, Handle::Closer closer, std::string_view what) const {
    return Handle(check_id(id, what), closer);
  }

 private:
  std::string file_;
  bool prefix_reads_ = false;
};

// ---- types ----

/// Variable-length UTF-8 string.
Handle string_type(const Context& cx);
/// Enum {FALSE = 0, TRUE = 1} over int8: what h5py and numpy read as bool.
Handle bool_type(const Context& cx);
/// The members of the archive's enum type for E: names from to_string(E) for the values 0, 1,
/// ... up to the first value whose name is "unknown". enum_type and results/README.md's list of
/// enum values both read them.
template <class E>
std::vector<std::pair<std::string_view, std::uint8_t>> enum_members() {
  std::vector<std::pair<std::string_view, std::uint8_t>> out;
  for (unsigned v = 0; v < 256; ++v) {
    const std::string_view name = to_string(static_cast<E>(v));
    if (name == "unknown") break;
    out.emplace_back(name, static_cast<std::uint8_t>(v));
  }
  return out;
}

/// Enum over uint8 with the members of enum_members<E>().
template <class E>
Handle enum_type(const Context& cx) {
  Handle type = cx.handle(H5Tenum_create(H5T_NATIVE_UINT8), H5Tclose, "cannot create an enum type");
  for (const auto& [name, value] : enum_members<E>()) {
    const std::string member(name);
    cx.check(H5Tenum_insert(type.get(), member.c_str(), &value),
             "cannot add enum member '" + member + "'");
  }
  return type;
}

// ---- columns (chunked, extendible, compressed datasets) ----

/// One dataset of `width` values a row (width 1: 1-D; else rows × width), appended to in
/// batches. Holds its own copy of the memory type.
class Column {
 public:
  Column() = default;
  /// Creates `name` under `group` (whose path is `group_path`) with no rows, chunked by
  /// `chunk_rows`, deflate level 4, shuffled when the element is wider than one byte and not
  /// a string.
  Column(const Context& cx, hid_t group, const std::string& group_path, const std::string& name,
         hid_t file_type, hid_t mem_type, hsize_t width, hsize_t chunk_rows);

  /// Appends `rows` rows read from `data` (rows × width values of the memory type).
  void append(const Context& cx, const void* data, hsize_t rows);
  template <class T>
  void append(const Context& cx, const std::vector<T>& values) {
    if (!values.empty()) append(cx, values.data(), values.size() / width_);
  }
  /// Closes the dataset now; returns H5Dclose's status.
  herr_t close() noexcept {
    mem_type_.close();
    return dataset_.close();
  }
  hsize_t rows() const noexcept { return rows_; }
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  Handle dataset_;
  Handle mem_type_;
  hsize_t width_ = 1;
  hsize_t rows_ = 0;
};

/// True when `group` has a link called `name`.
bool has_link(const Context& cx, hid_t group, const std::string& group_path,
              const std::string& name);
/// Opens the group `name` under `parent`; ArchiveError "missing group PATH" when absent.
Handle open_group(const Context& cx, hid_t parent, const std::string& parent_path,
                  const std::string& name);
/// Creates the group `name` under `parent`, tracking attribute creation order.
Handle create_group(const Context& cx, hid_t parent, const std::string& parent_path,
                    const std::string& name);

/// A dataset opened for reading, its shape checked.
struct OpenDataset {
  Handle dataset;
  hsize_t rows = 0;         ///< rows to read
  hsize_t stored_rows = 0;  ///< rows in the file (more than `rows` only for prefix reads)
  hsize_t width = 1;
  std::string path;
};
inline constexpr hsize_t any_rows = static_cast<hsize_t>(-1);
/// Opens `name` under `group` and checks that its type class is the memory type's, that it
/// has `width` values a row and (unless expected_rows is any_rows) `expected_rows` rows.
OpenDataset open_dataset(const Context& cx, hid_t group, const std::string& group_path,
                         const std::string& name, hid_t mem_type, hsize_t width,
                         hsize_t expected_rows);
/// Reads the whole dataset into `buffer` (rows × width values of the memory type).
void read_all(const Context& cx, const OpenDataset& d, hid_t mem_type, void* buffer);

/// Reads a whole dataset into `T`s (T's size must be the memory type's).
template <class T>
std::vector<T> read_column(const Context& cx, hid_t group, const std::string& group_path,
                           const std::string& name, hid_t mem_type,
                           hsize_t expected_rows = any_rows, hsize_t width = 1) {
  const OpenDataset d = open_dataset(cx, group, group_path, name, mem_type, width, expected_rows);
  if (H5Tget_size(mem_type) != sizeof(T))
    cx.error("dataset " + d.path + ": memory type does not match the element size");
  std::vector<T> values(d.rows * width);
  if (!values.empty()) read_all(cx, d, mem_type, values.data());
  return values;
}
/// Reads a 1-D variable-length string dataset.
std::vector<std::string> read_string_column(const Context& cx, hid_t group,
                                            const std::string& group_path, const std::string& name,
                                            hsize_t expected_rows);

// ---- attributes (scalars and 1-D string arrays) ----

void write_attr_string(const Context& cx, hid_t obj, const std::string& obj_path,
                       const std::string& name, const std::string& value);
void write_attr_strings(const Context& cx, hid_t obj, const std::string& obj_path,
                        const std::string& name, const std::vector<std::string>& values);
void write_attr_i32(const Context& cx, hid_t obj, const std::string& obj_path,
                    const std::string& name, std::int32_t value);
void write_attr_u64(const Context& cx, hid_t obj, const std::string& obj_path,
                    const std::string& name, std::uint64_t value);
void write_attr_u8(const Context& cx, hid_t obj, const std::string& obj_path,
                   const std::string& name, std::uint8_t value);
void write_attr_f64(const Context& cx, hid_t obj, const std::string& obj_path,
                    const std::string& name, double value);

bool has_attr(const Context& cx, hid_t obj, const std::string& obj_path, const std::string& name);
/// Attribute names in creation order (name order when the object does not track it).
std::vector<std::string> attr_names(const Context& cx, hid_t obj, const std::string& obj_path);
/// The type class of an attribute (H5T_STRING, H5T_INTEGER, ...).
H5T_class_t attr_class(const Context& cx, hid_t obj, const std::string& obj_path,
                       const std::string& name);

std::string read_attr_string(const Context& cx, hid_t obj, const std::string& obj_path,
                             const std::string& name);
std::vector<std::string> read_attr_strings(const Context& cx, hid_t obj,
                                           const std::string& obj_path, const std::string& name);
std::int32_t read_attr_i32(const Context& cx, hid_t obj, const std::string& obj_path,
                           const std::string& name);
std::uint64_t read_attr_u64(const Context& cx, hid_t obj, const std::string& obj_path,
                            const std::string& name);
std::uint8_t read_attr_u8(const Context& cx, hid_t obj, const std::string& obj_path,
                          const std::string& name);
double read_attr_f64(const Context& cx, hid_t obj, const std::string& obj_path,
                     const std::string& name);

}  // namespace gjklab::experiment::h5
