#include "hdf5_util.hpp"

#include <algorithm>
#include <array>

namespace gjklab::experiment::h5 {

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    close();
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = -1;
  }
  return *this;
}

herr_t Handle::close() noexcept {
  herr_t status = 0;
  if (id_ >= 0 && closer_ != nullptr) status = closer_(id_);
  id_ = -1;
  return status;
}

void quiet_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

namespace {

// The most specific message on HDF5's error stack (walked from the innermost call outward).
herr_t first_message(unsigned n, const H5E_error2_t* err, void* client) {
  auto* out = static_cast<std::string*>(client);
  if (n == 0 && err != nullptr && err->desc != nullptr) *out = err->desc;
  return 0;
}

std::string hdf5_message() {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_message, &message);
  H5Eclear2(H5E_DEFAULT);
  return message;
}

std::string attr_label(const std::string& obj_path, const std::string& name) {
  return "attribute '" + name + "' of " + obj_path;
}

// Creates (replacing nothing: the name must be new) and writes one attribute.
void write_attr(const Context& cx, hid_t obj, const std::string& obj_path, const std::string& name,
                hid_t file_type, hid_t mem_type, hid_t space, const void* data) {
  const std::string label = attr_label(obj_path, name);
  // An existing attribute (a checkpoint counter) is overwritten in place: same type and shape.
  const bool exists = cx.check_tri(H5Aexists(obj, name.c_str()), "cannot look up " + label);
  Handle attr =
      exists ? cx.handle(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open " + label)
             : cx.handle(H5Acreate2(obj, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT),
                         H5Aclose, "cannot create " + label);
  if (H5Sget_simple_extent_npoints(space) > 0)  // an empty array has nothing to write
    cx.check(H5Awrite(attr.get(), mem_type, data), "cannot write " + label);
  cx.check(attr.close(), "cannot close " + label);
}

void write_scalar(const Context& cx, hid_t obj, const std::string& obj_path,
                  const std::string& name, hid_t file_type, hid_t mem_type, const void* data) {
  Handle space = cx.handle(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a dataspace");
  write_attr(cx, obj, obj_path, name, file_type, mem_type, space.get(), data);
}

// Opens an attribute that must exist and be a scalar of the given type class.
Handle open_attr(const Context& cx, hid_t obj, const std::string& obj_path, const std::string& name,
                 H5T_class_t expected, bool scalar) {
  const std::string label = attr_label(obj_path, name);
  if (!has_attr(cx, obj, obj_path, name)) cx.error("missing " + label);
  Handle attr =
      cx.handle(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open " + label);
  Handle type = cx.handle(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of " + label);
  if (H5Tget_class(type.get()) != expected) cx.error(label + " has an unexpected type");
  Handle space = cx.handle(H5Aget_space(attr.get()), H5Sclose, "cannot read the shape of " + label);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (scalar ? rank != 0 : rank != 1) cx.error(label + " has an unexpected shape");
  return attr;
}

template <class T>
T read_scalar(const Context& cx, hid_t obj, const std::string& obj_path, const std::string& name,
              H5T_class_t expected, hid_t mem_type) {
  Handle attr = open_attr(cx, obj, obj_path, name, expected, true);
  T value{};
  cx.check(H5Aread(attr.get(), mem_type, &value), "cannot read " + attr_label(obj_path, name));
  return value;
}

// Frees the strings HDF5 allocated for a variable-length read, whatever happens after it.
class VlenGuard {
 public:
  VlenGuard(hid_t type, hid_t space, void* buffer) : type_(type), space_(space), buffer_(buffer) {}
  ~VlenGuard() { H5Dvlen_reclaim(type_, space_, H5P_DEFAULT, buffer_); }
  VlenGuard(const VlenGuard&) = delete;
  VlenGuard& operator=(const VlenGuard&) = delete;

 private:
  hid_t type_, space_;
  void* buffer_;
};

std::vector<std::string> to_strings(const std::vector<char*>& raw) {
  std::vector<std::string> out;
  out.reserve(raw.size());
  for (const char* s : raw)
    out.emplace_back(s == nullptr ? "" : s);
  return out;
}

}  // namespace

void Context::fail(std::string_view what) const {
  const std::string detail = hdf5_message();
  std::string message = "archive " + file_ + ": " + std::string(what);
  if (!detail.empty()) message += " (HDF5: " + detail + ")";
  throw ArchiveError(message);
}

void Context::error(std::string_view what) const {
  throw ArchiveError("archive " + file_ + ": " + std::string(what));
}

Handle string_type(const Context& cx) {
  Handle type = cx.handle(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create the string type");
  cx.check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot create the string type");
  cx.check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot create the string type");
  return type;
}

Handle bool_type(const Context& cx) {
  Handle type = cx.handle(H5Tenum_create(H5T_NATIVE_INT8), H5Tclose, "cannot create the bool type");
  const std::int8_t f = 0, t = 1;
  cx.check(H5Tenum_insert(type.get(), "FALSE", &f), "cannot create the bool type");
  cx.check(H5Tenum_insert(type.get(), "TRUE", &t), "cannot create the bool type");
  return type;
}

// ---- columns ----

Column::Column(const Context& cx, hid_t group, const std::string& group_path,
               const std::string& name, hid_t file_type, hid_t mem_type, hsize_t width,
               hsize_t chunk_rows)
    : path_(group_path + "/" + name), width_(width) {
  const std::string label = "dataset " + path_;
  const int rank = width == 1 ? 1 : 2;
  const std::array<hsize_t, 2> dims{0, width};
  const std::array<hsize_t, 2> max_dims{H5S_UNLIMITED, width};
  const std::array<hsize_t, 2> chunk{std::max<hsize_t>(chunk_rows, 1), width};
  Handle space = cx.handle(H5Screate_simple(rank, dims.data(), max_dims.data()), H5Sclose,
                           "cannot create the dataspace of " + label);
  Handle dcpl = cx.handle(H5Pcreate(H5P_DATASET_CREATE), H5Pclose,
                          "cannot create the properties of " + label);
  cx.check(H5Pset_chunk(dcpl.get(), rank, chunk.data()), "cannot set the chunks of " + label);
  const bool is_string = H5Tget_class(file_type) == H5T_STRING;
  if (!is_string && H5Tget_size(file_type) > 1)
    cx.check(H5Pset_shuffle(dcpl.get()), "cannot set the shuffle filter of " + label);
  cx.check(H5Pset_deflate(dcpl.get(), 4), "cannot set the deflate filter of " + label);
  dataset_ = cx.handle(
      H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
      H5Dclose, "cannot create " + label);
  mem_type_ = cx.handle(H5Tcopy(mem_type), H5Tclose, "cannot copy the memory type of " + label);
}

void Column::append(const Context& cx, const void* data, hsize_t rows) {
  if (rows == 0) return;
  const std::string label = "dataset " + path_;
  const int rank = width_ == 1 ? 1 : 2;
  const std::array<hsize_t, 2> new_dims{rows_ + rows, width_};
  cx.check(H5Dset_extent(dataset_.get(), new_dims.data()), "cannot extend " + label);
  Handle file_space =
      cx.handle(H5Dget_space(dataset_.get()), H5Sclose, "cannot read the dataspace of " + label);
  const std::array<hsize_t, 2> start{rows_, 0};
  const std::array<hsize_t, 2> count{rows, width_};
  cx.check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                               count.data(), nullptr),
           "cannot select the new rows of " + label);
  Handle mem_space = cx.handle(H5Screate_simple(rank, count.data(), nullptr), H5Sclose,
                               "cannot create a dataspace for " + label);
  cx.check(H5Dwrite(dataset_.get(), mem_type_.get(), mem_space.get(), file_space.get(), H5P_DEFAULT,
                    data),
           "cannot write " + label);
  rows_ += rows;
}

bool has_link(const Context& cx, hid_t group, const std::string& group_path,
              const std::string& name) {
  return cx.check_tri(H5Lexists(group, name.c_str(), H5P_DEFAULT),
                      "cannot look up " + group_path + "/" + name);
}

namespace {
std::string child_path(const std::string& parent_path, const std::string& name) {
  return parent_path == "/" ? "/" + name : parent_path + "/" + name;
}

/// Deflate, the one filter of the archives that shrinks data, stores at most 1032 bytes in one
/// (zlib's limit), and the writer fills every row it adds.
constexpr hsize_t kMaxDeflateRatio = 1032;

/// Refuses a row count whose data (at the file type's size) would take more than kMaxDeflateRatio
/// times the whole file: a corrupt count, which the reader would otherwise allocate (a damaged
/// dimension of a 98 kB file asked for 48 TB).
void check_rows_fit(const Context& cx, const OpenDataset& d, hid_t file_type,
                    const std::string& label) {
  const Handle file =
      cx.handle(H5Iget_file_id(d.dataset.get()), H5Fclose, "cannot find the file of " + label);
  hsize_t file_bytes = 0;
  cx.check(H5Fget_filesize(file.get(), &file_bytes), "cannot read the size of the file");
  const hsize_t row_bytes = std::max<hsize_t>(1, d.width * H5Tget_size(file_type));
  if (d.rows > kMaxDeflateRatio * file_bytes / row_bytes)
    cx.error(label + " has " + std::to_string(d.rows) + " rows: more than a file of " +
             std::to_string(file_bytes) + " bytes can hold");
}
}  // namespace

Handle open_group(const Context& cx, hid_t parent, const std::string& parent_path,
                  const std::string& name) {
  const std::string path = child_path(parent_path, name);
  if (!has_link(cx, parent, parent_path, name)) cx.error("missing group " + path);
  return cx.handle(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose,
                   "cannot open group " + path);
}

Handle create_group(const Context& cx, hid_t parent, const std::string& parent_path,
                    const std::string& name) {
  const std::string path = child_path(parent_path, name);
  Handle gcpl = cx.handle(H5Pcreate(H5P_GROUP_CREATE), H5Pclose,
                          "cannot create the properties of group " + path);
  cx.check(H5Pset_attr_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
           "cannot track the attribute order of group " + path);
  return cx.handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose,
                   "cannot create group " + path);
}

OpenDataset open_dataset(const Context& cx, hid_t group, const std::string& group_path,
                         const std::string& name, hid_t mem_type, hsize_t width,
                         hsize_t expected_rows) {
  OpenDataset d;
  d.path = child_path(group_path, name);
  const std::string label = "dataset " + d.path;
  if (!has_link(cx, group, group_path, name)) cx.error("missing " + label);
  d.dataset =
      cx.handle(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open " + label);
  Handle type =
      cx.handle(H5Dget_type(d.dataset.get()), H5Tclose, "cannot read the type of " + label);
  if (H5Tget_class(type.get()) != H5Tget_class(mem_type))
    cx.error(label + " has an unexpected type class");
  Handle space =
      cx.handle(H5Dget_space(d.dataset.get()), H5Sclose, "cannot read the shape of " + label);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::array<hsize_t, 2> dims{0, 0};
  if (rank != (width == 1 ? 1 : 2)) cx.error(label + " has an unexpected rank");
  cx.check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr),
           "cannot read the shape of " + label);
  if (width != 1 && dims[1] != width)
    cx.error(label + " has " + std::to_string(dims[1]) + " columns, expected " +
             std::to_string(width));
  const bool prefix = cx.prefix_reads() && expected_rows != any_rows && dims[0] > expected_rows;
  if (expected_rows != any_rows && dims[0] != expected_rows && !prefix)
    cx.error(label + " has " + std::to_string(dims[0]) + " rows, expected " +
             std::to_string(expected_rows));
  d.stored_rows = dims[0];
  d.rows = prefix ? expected_rows : dims[0];
  d.width = width;
  check_rows_fit(cx, d, type.get(), label);
  return d;
}

namespace {

/// The file and memory dataspaces of the first d.rows rows.
std::pair<Handle, Handle> row_spaces(const Context& cx, const OpenDataset& d) {
  Handle file_space =
      cx.handle(H5Dget_space(d.dataset.get()), H5Sclose, "cannot read the shape of " + d.path);
  const int rank = d.width == 1 ? 1 : 2;
  const hsize_t start[2] = {0, 0};
  const hsize_t count[2] = {d.rows, d.width};
  cx.check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
           "cannot select rows of " + d.path);
  Handle mem_space = cx.handle(H5Screate_simple(rank, count, nullptr), H5Sclose,
                               "cannot create a dataspace for " + d.path);
  return {std::move(file_space), std::move(mem_space)};
}

}  // namespace

void read_all(const Context& cx, const OpenDataset& d, hid_t mem_type, void* buffer) {
  if (d.rows == d.stored_rows) {
    cx.check(H5Dread(d.dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer),
             "cannot read dataset " + d.path);
    return;
  }
  const auto [file_space, mem_space] = row_spaces(cx, d);
  cx.check(
      H5Dread(d.dataset.get(), mem_type, mem_space.get(), file_space.get(), H5P_DEFAULT, buffer),
      "cannot read dataset " + d.path);
}

std::vector<std::string> read_string_column(const Context& cx, hid_t group,
                                            const std::string& group_path, const std::string& name,
                                            hsize_t expected_rows) {
  Handle type = string_type(cx);
  const OpenDataset d = open_dataset(cx, group, group_path, name, type.get(), 1, expected_rows);
  std::vector<char*> raw(d.rows, nullptr);
  if (raw.empty()) return {};
  const hsize_t rows = d.rows;
  Handle space = cx.handle(H5Screate_simple(1, &rows, nullptr), H5Sclose,
                           "cannot create a dataspace for " + d.path);
  const VlenGuard guard(type.get(), space.get(), raw.data());
  read_all(cx, d, type.get(), raw.data());
  return to_strings(raw);
}

// ---- attributes ----

void write_attr_string(const Context& cx, hid_t obj, const std::string& obj_path,
                       const std::string& name, const std::string& value) {
  Handle type = string_type(cx);
  const char* data = value.c_str();
  write_scalar(cx, obj, obj_path, name, type.get(), type.get(), &data);
}

void write_attr_strings(const Context& cx, hid_t obj, const std::string& obj_path,
                        const std::string& name, const std::vector<std::string>& values) {
  Handle type = string_type(cx);
  std::vector<const char*> data;
  data.reserve(values.size());
  for (const auto& v : values)
    data.push_back(v.c_str());
  const hsize_t n = values.size();
  Handle space = cx.handle(H5Screate_simple(1, &n, nullptr), H5Sclose, "cannot create a dataspace");
  write_attr(cx, obj, obj_path, name, type.get(), type.get(), space.get(), data.data());
}

void write_attr_i32(const Context& cx, hid_t obj, const std::string& obj_path,
                    const std::string& name, std::int32_t value) {
  write_scalar(cx, obj, obj_path, name, H5T_STD_I32LE, H5T_NATIVE_INT32, &value);
}

void write_attr_u64(const Context& cx, hid_t obj, const std::string& obj_path,
                    const std::string& name, std::uint64_t value) {
  write_scalar(cx, obj, obj_path, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value);
}

void write_attr_u8(const Context& cx, hid_t obj, const std::string& obj_path,
                   const std::string& name, std::uint8_t value) {
  write_scalar(cx, obj, obj_path, name, H5T_STD_U8LE, H5T_NATIVE_UINT8, &value);
}

void write_attr_f64(const Context& cx, hid_t obj, const std::string& obj_path,
                    const std::string& name, double value) {
  write_scalar(cx, obj, obj_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

bool has_attr(const Context& cx, hid_t obj, const std::string& obj_path, const std::string& name) {
  return cx.check_tri(H5Aexists(obj, name.c_str()), "cannot look up " + attr_label(obj_path, name));
}

namespace {
herr_t collect_name(hid_t, const char* name, const H5A_info_t*, void* client) {
  static_cast<std::vector<std::string>*>(client)->emplace_back(name);
  return 0;
}
}  // namespace

std::vector<std::string> attr_names(const Context& cx, hid_t obj, const std::string& obj_path) {
  std::vector<std::string> names;
  if (H5Aiterate2(obj, H5_INDEX_CRT_ORDER, H5_ITER_INC, nullptr, collect_name, &names) >= 0)
    return names;
  H5Eclear2(H5E_DEFAULT);  // creation order not tracked: fall back to name order
  names.clear();
  cx.check(H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names),
           "cannot list the attributes of " + obj_path);
  return names;
}

H5T_class_t attr_class(const Context& cx, hid_t obj, const std::string& obj_path,
                       const std::string& name) {
  const std::string label = attr_label(obj_path, name);
  Handle attr =
      cx.handle(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open " + label);
  Handle type = cx.handle(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of " + label);
  return H5Tget_class(type.get());
}

std::string read_attr_string(const Context& cx, hid_t obj, const std::string& obj_path,
                             const std::string& name) {
  Handle attr = open_attr(cx, obj, obj_path, name, H5T_STRING, true);
  Handle file_type = cx.handle(H5Aget_type(attr.get()), H5Tclose,
                               "cannot read the type of " + attr_label(obj_path, name));
  if (H5Tis_variable_str(file_type.get()) <= 0)
    cx.error(attr_label(obj_path, name) + " is not a variable-length string");
  Handle type = string_type(cx);
  Handle space = cx.handle(H5Aget_space(attr.get()), H5Sclose,
                           "cannot read the shape of " + attr_label(obj_path, name));
  std::vector<char*> raw(1, nullptr);
  const VlenGuard guard(type.get(), space.get(), raw.data());
  cx.check(H5Aread(attr.get(), type.get(), raw.data()),
           "cannot read " + attr_label(obj_path, name));
  return to_strings(raw).front();
}

std::vector<std::string> read_attr_strings(const Context& cx, hid_t obj,
                                           const std::string& obj_path, const std::string& name) {
  const std::string label = attr_label(obj_path, name);
  Handle attr = open_attr(cx, obj, obj_path, name, H5T_STRING, false);
  Handle file_type =
      cx.handle(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of " + label);
  if (H5Tis_variable_str(file_type.get()) <= 0)
    cx.error(label + " is not a variable-length string array");
  Handle space = cx.handle(H5Aget_space(attr.get()), H5Sclose, "cannot read the shape of " + label);
  hsize_t n = 0;
  cx.check(H5Sget_simple_extent_dims(space.get(), &n, nullptr),
           "cannot read the shape of " + label);
  if (n == 0) return {};
  Handle type = string_type(cx);
  std::vector<char*> raw(n, nullptr);
  const VlenGuard guard(type.get(), space.get(), raw.data());
  cx.check(H5Aread(attr.get(), type.get(), raw.data()), "cannot read " + label);
  return to_strings(raw);
}

std::int32_t read_attr_i32(const Context& cx, hid_t obj, const std::string& obj_path,
                           const std::string& name) {
  return read_scalar<std::int32_t>(cx, obj, obj_path, name, H5T_INTEGER, H5T_NATIVE_INT32);
}

std::uint64_t read_attr_u64(const Context& cx, hid_t obj, const std::string& obj_path,
                            const std::string& name) {
  return read_scalar<std::uint64_t>(cx, obj, obj_path, name, H5T_INTEGER, H5T_NATIVE_UINT64);
}

std::uint8_t read_attr_u8(const Context& cx, hid_t obj, const std::string& obj_path,
                          const std::string& name) {
  return read_scalar<std::uint8_t>(cx, obj, obj_path, name, H5T_INTEGER, H5T_NATIVE_UINT8);
}

double read_attr_f64(const Context& cx, hid_t obj, const std::string& obj_path,
                     const std::string& name) {
  return read_scalar<double>(cx, obj, obj_path, name, H5T_FLOAT, H5T_NATIVE_DOUBLE);
}

}  // namespace gjklab::experiment::h5
