#include "io/h5_file.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <numeric>

namespace iga::io::h5 {

// --- errors ------------------------------------------------------------------

ErrorSilencer::ErrorSilencer()
{
    H5Eget_auto2(H5E_DEFAULT, &previous_func_, &previous_data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

ErrorSilencer::~ErrorSilencer() { H5Eset_auto2(H5E_DEFAULT, previous_func_, previous_data_); }

namespace {

herr_t take_first_description(unsigned /*n*/, const H5E_error2_t* error, void* client)
{
    auto* out = static_cast<std::string*>(client);
    if (out->empty() && error->desc != nullptr && error->desc[0] != '\0')
        *out = error->desc;
    return 0;
}

}  // namespace

std::string last_error_description()
{
    const hid_t stack = H5Eget_current_stack();
    if (stack < 0)
        return {};
    std::string description;
    // Upward = from the innermost function, where the cause (e.g. errno) is described.
    H5Ewalk2(stack, H5E_WALK_UPWARD, take_first_description, &description);
    H5Eclose_stack(stack);
    return description;
}

namespace {

/// The errno of a failed system call as HDF5's file driver describes it
/// ("... errno = 28, error message = 'No space left on device' ..."), or 0.
int described_errno(const std::string& description)
{
    const std::string key = "errno = ";
    const std::size_t at = description.find(key);
    return at == std::string::npos ? 0 : std::atoi(description.c_str() + at + key.size());
}

/// The file HDF5's file driver names ("... filename = '<path>', ..."), or "".
std::string described_file(const std::string& description)
{
    const std::string key = "filename = '";
    const std::size_t at = description.find(key);
    if (at == std::string::npos)
        return {};
    const std::size_t end = description.find('\'', at + key.size());
    return end == std::string::npos ? std::string() : description.substr(at + key.size(), end - at - key.size());
}

}  // namespace

[[noreturn]] void throw_described(const std::string& what, const std::string& description)
{
    // A write the file system refused is the run's fate, not a bug of ours: said in
    // a line (the driver's description also lists buffers and offsets).
    const int code = described_errno(description);
    if (code == ENOSPC || code == EDQUOT || code == EFBIG || code == EROFS || code == EIO) {
        const std::string file = described_file(description);
        throw StorageError(what + (file.empty() ? "" : " (" + file + ")") + ": " + std::strerror(code));
    }
    throw Error(description.empty() ? what : what + ": " + description);
}

void throw_error(const std::string& what)
{
    throw_described(what, last_error_description());
}

void no_shutdown_at_exit()
{
    // HDF5 closes the files still open at exit; one whose close failed (a full disk)
    // it closes again and crashes in (HDF5 1.10). Every file igacontact writes is
    // closed explicitly, so there is nothing left for the exit to do.
    H5dont_atexit();
}

// --- Handle ------------------------------------------------------------------

Handle::Handle(hid_t id, Closer closer, const std::string& what) : id_(id), closer_(closer)
{
    if (id_ < 0)
        throw_error(what);
}

Handle::Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = H5I_INVALID_HID; }

Handle& Handle::operator=(Handle&& other) noexcept
{
    if (this != &other) {
        reset();
        id_ = other.id_;
        closer_ = other.closer_;
        other.id_ = H5I_INVALID_HID;
    }
    return *this;
}

void Handle::reset() noexcept
{
    if (id_ >= 0 && closer_ != nullptr)
        closer_(id_);
    id_ = H5I_INVALID_HID;
}

void Handle::close()
{
    if (id_ < 0)
        return;
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    if (closer_(id) < 0)
        throw_error("cannot close HDF5 object");
}

// --- files, groups, links ----------------------------------------------------

namespace {

Handle strong_close_access()
{
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "cannot create a file access property list");
    // Strong: closing the file closes every object still open in it, so the file is complete on disk.
    if (H5Pset_fclose_degree(fapl.id(), H5F_CLOSE_STRONG) < 0)
        throw_error("cannot set the file close degree");
    return fapl;
}

std::string object_name(hid_t location, const std::string& name)
{
    const ssize_t size = H5Iget_name(location, nullptr, 0);
    std::string base = "?";
    if (size > 0) {
        base.assign(static_cast<std::size_t>(size) + 1, '\0');
        H5Iget_name(location, base.data(), base.size());
        base.resize(static_cast<std::size_t>(size));
    }
    if (name.empty() || name == ".")
        return base;
    if (name.front() == '/')
        return name;
    return base == "/" ? "/" + name : base + "/" + name;
}

// Throws like throw_error, naming the object only now: H5Iget_name is cheap for an object
// opened by path but searches the WHOLE file for one reached through an anonymous group
// (the steps under construction), which made every write cost O(file size). The HDF5
// error description is taken first: the name lookup clears HDF5's error stack.
[[noreturn]] void fail_on(const char* action, hid_t location, const std::string& name, const std::string& suffix = "")
{
    const std::string description = last_error_description();
    throw_described(std::string(action) + " " + object_name(location, name) + suffix, description);
}

Handle string_type()
{
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create a string type");
    if (H5Tset_size(type.id(), H5T_VARIABLE) < 0 || H5Tset_cset(type.id(), H5T_CSET_UTF8) < 0)
        throw_error("cannot set up a variable-length UTF-8 string type");
    return type;
}

Handle make_space(const std::vector<hsize_t>& dims)
{
    if (dims.empty())
        return Handle(H5Screate(H5S_SCALAR), H5Sclose, "cannot create a scalar dataspace");
    return Handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                  "cannot create a dataspace");
}

hsize_t product(const std::vector<hsize_t>& dims)
{
    return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

// Writes a dataset of `file_type` from `buffer` in `memory_type`; zero-size datasets skip H5Dwrite.
void write_raw_dataset(hid_t location, const std::string& name, hid_t file_type, hid_t memory_type,
                       const std::vector<hsize_t>& dims, const void* buffer)
{
    Handle space = make_space(dims);
    const hid_t id = H5Dcreate2(location, name.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (id < 0)
        fail_on("cannot write dataset", location, name);
    Handle set(id, H5Dclose, "");
    if (product(dims) > 0 && H5Dwrite(set.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer) < 0)
        fail_on("cannot write dataset", location, name);
    set.close();
}

// Writes (replacing any existing attribute of that name) an attribute.
void write_raw_attribute(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type,
                         const std::vector<hsize_t>& dims, const void* buffer)
{
    const htri_t present = H5Aexists(object, name.c_str());
    if (present < 0 || (present > 0 && H5Adelete(object, name.c_str()) < 0))
        fail_on("cannot write attribute", object, "", "@" + name);
    Handle space = make_space(dims);
    const hid_t id = H5Acreate2(object, name.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT);
    if (id < 0)
        fail_on("cannot write attribute", object, "", "@" + name);
    Handle attribute(id, H5Aclose, "");
    if (product(dims) > 0 && H5Awrite(attribute.id(), memory_type, buffer) < 0)
        fail_on("cannot write attribute", object, "", "@" + name);
    attribute.close();
}

}  // namespace

Handle create_file(const std::string& path)
{
    Handle fapl = strong_close_access();
    // A small fixed-size metadata cache: H5Fflush visits every entry of the cache, whose
    // default size grows to 32 MB as a run adds steps, so a flush per step cost more with
    // every step. With the cache capped, old step headers are evicted (written) as new ones
    // come and a flush costs the same at step 10 and at step 10 000 (scripts/bench_output.py).
    // The cache still grows for an entry too large for it (flash increment): one group
    // header of a body of 2000 patches is, and a cache capped below an entry wrote a
    // file HDF5 could not read back ("incorrect metadata checksum").
    constexpr std::size_t metadata_cache_bytes = 256 * 1024;
    constexpr std::size_t largest_cache_bytes = 64 * 1024 * 1024;
    H5AC_cache_config_t config;
    config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
    if (H5Pget_mdc_config(fapl.id(), &config) < 0)
        throw_error("cannot read the metadata cache configuration");
    config.set_initial_size = true;
    config.initial_size = metadata_cache_bytes;
    config.min_size = metadata_cache_bytes;
    config.max_size = largest_cache_bytes;
    config.incr_mode = H5C_incr__off;
    config.flash_incr_mode = H5C_flash_incr__add_space;
    config.decr_mode = H5C_decr__off;
    if (H5Pset_mdc_config(fapl.id(), &config) < 0)
        throw_error("cannot set the metadata cache configuration");
    // The HDF5 1.8 file format (readable by HDF5 >= 1.8, h5py): groups with many members
    // (/steps) use dense link storage (fractal heap + B-tree) instead of one local heap
    // rewritten whole at every flush, and object headers are smaller (files ~3x smaller).
    if (H5Pset_libver_bounds(fapl.id(), H5F_LIBVER_V18, H5F_LIBVER_V18) < 0)
        throw_error("cannot set the HDF5 file format version");
    return Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id()), H5Fclose,
                  "cannot create HDF5 file " + path);
}

Handle open_file(const std::string& path)
{
    Handle fapl = strong_close_access();
    return Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.id()), H5Fclose, "cannot open HDF5 file " + path);
}

Handle open_file_for_update(const std::string& path)
{
    Handle fapl = strong_close_access();
    return Handle(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id()), H5Fclose, "cannot open HDF5 file " + path);
}

Handle create_group(hid_t parent, const std::string& name)
{
    const hid_t id = H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (id < 0)
        fail_on("cannot create group", parent, name);
    return Handle(id, H5Gclose, "");
}

Handle open_object(hid_t parent, const std::string& path)
{
    const hid_t id = H5Oopen(parent, path.c_str(), H5P_DEFAULT);
    if (id < 0)
        fail_on("cannot open", parent, path);
    return Handle(id, H5Oclose, "");
}

bool exists(hid_t location, const std::string& path)
{
    if (path.empty() || path == "/" || path == ".")
        return true;
    // H5Lexists needs every intermediate link to exist, so check the prefixes in turn.
    std::string prefix = path.front() == '/' ? "/" : "";
    std::size_t start = prefix.size();
    while (start < path.size()) {
        std::size_t end = path.find('/', start);
        if (end == std::string::npos)
            end = path.size();
        if (end > start) {
            if (!prefix.empty() && prefix.back() != '/')
                prefix += '/';
            prefix += path.substr(start, end - start);
            if (H5Lexists(location, prefix.c_str(), H5P_DEFAULT) <= 0)
                return false;
        }
        start = end + 1;
    }
    return H5Oexists_by_name(location, path.c_str(), H5P_DEFAULT) > 0;
}

ObjectKind object_kind(hid_t object)
{
    switch (H5Iget_type(object)) {
    case H5I_GROUP:
    case H5I_FILE:
        return ObjectKind::group;
    case H5I_DATASET:
        return ObjectKind::dataset;
    default:
        return ObjectKind::other;
    }
}

namespace {
herr_t collect_link_name(hid_t /*group*/, const char* name, const H5L_info_t* /*info*/, void* client)
{
    static_cast<std::vector<std::string>*>(client)->emplace_back(name);
    return 0;
}
}  // namespace

std::vector<std::string> link_names(hid_t group)
{
    // One pass (by index, one H5Lget_name_by_idx per link, sorted the whole group's
    // links again at every call: 55 s for a group of 5000 patches).
    std::vector<std::string> names;
    hsize_t index = 0;
    if (H5Literate(group, H5_INDEX_NAME, H5_ITER_NATIVE, &index, collect_link_name, &names) < 0)
        throw_error("cannot list the links of " + object_name(group, ""));
    std::sort(names.begin(), names.end());
    return names;
}

namespace {
herr_t collect_attribute_name(hid_t /*object*/, const char* name, const H5A_info_t* /*info*/, void* client)
{
    static_cast<std::vector<std::string>*>(client)->emplace_back(name);
    return 0;
}
}  // namespace

std::vector<std::string> attribute_names(hid_t object)
{
    std::vector<std::string> names;
    hsize_t index = 0;
    if (H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute_name, &names) < 0)
        throw_error("cannot list the attributes of " + object_name(object, ""));
    std::sort(names.begin(), names.end());
    return names;
}

bool same_object(hid_t a, hid_t b)
{
#if H5_VERSION_GE(1, 12, 0)
    H5O_info2_t info_a, info_b;
    if (H5Oget_info3(a, &info_a, H5O_INFO_BASIC) < 0 || H5Oget_info3(b, &info_b, H5O_INFO_BASIC) < 0)
        throw_error("cannot read HDF5 object info");
    int order = 0;
    if (H5Otoken_cmp(a, &info_a.token, &info_b.token, &order) < 0)
        throw_error("cannot compare HDF5 object tokens");
    return info_a.fileno == info_b.fileno && order == 0;
#else
    H5O_info_t info_a, info_b;
    if (H5Oget_info2(a, &info_a, H5O_INFO_BASIC) < 0 || H5Oget_info2(b, &info_b, H5O_INFO_BASIC) < 0)
        throw_error("cannot read HDF5 object info");
    return info_a.fileno == info_b.fileno && info_a.addr == info_b.addr;
#endif
}

void replace_hard_link(hid_t location, const std::string& target, const std::string& link_name)
{
    const htri_t present = H5Lexists(location, link_name.c_str(), H5P_DEFAULT);
    if (present < 0 || (present > 0 && H5Ldelete(location, link_name.c_str(), H5P_DEFAULT) < 0))
        fail_on("cannot link", location, link_name, " to " + target);
    if (H5Lcreate_hard(location, target.c_str(), location, link_name.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0)
        fail_on("cannot link", location, link_name, " to " + target);
}

// --- writing -----------------------------------------------------------------

void write_dataset(hid_t location, const std::string& name, const RowMatrix& values)
{
    const std::vector<hsize_t> dims{static_cast<hsize_t>(values.rows()), static_cast<hsize_t>(values.cols())};
    write_raw_dataset(location, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, values.data());
}

void write_dataset(hid_t location, const std::string& name, const Vector& values)
{
    write_raw_dataset(location, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {static_cast<hsize_t>(values.size())},
                      values.data());
}

void write_dataset(hid_t location, const std::string& name, std::span<const double> values,
                   const std::vector<hsize_t>& dims)
{
    IGA_CHECK(product(dims) == values.size(), "dataset " + name + ": dims do not match the number of values");
    write_raw_dataset(location, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, values.data());
}

void write_dataset(hid_t location, const std::string& name, std::span<const int> values)
{
    write_raw_dataset(location, name, H5T_STD_I32LE, H5T_NATIVE_INT, {static_cast<hsize_t>(values.size())},
                      values.data());
}

void write_dataset(hid_t location, const std::string& name, std::span<const int> values,
                   const std::vector<hsize_t>& dims)
{
    write_raw_dataset(location, name, H5T_STD_I32LE, H5T_NATIVE_INT, dims, values.data());
}

void write_string_dataset(hid_t location, const std::string& name, const std::string& text)
{
    Handle type = string_type();
    const char* pointer = text.c_str();
    write_raw_dataset(location, name, type.id(), type.id(), {}, &pointer);
}

void write_string_dataset(hid_t location, const std::string& name, const std::vector<std::string>& values,
                          const std::vector<hsize_t>& dims)
{
    IGA_CHECK(product(dims) == values.size(), "dataset " + name + ": dims do not match the number of strings");
    Handle type = string_type();
    std::vector<const char*> pointers;
    for (const std::string& value : values)
        pointers.push_back(value.c_str());
    write_raw_dataset(location, name, type.id(), type.id(), dims, pointers.data());
}

void write_attribute(hid_t object, const std::string& name, double value)
{
    write_raw_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {}, &value);
}

void write_attribute(hid_t object, const std::string& name, int value)
{
    write_raw_attribute(object, name, H5T_STD_I32LE, H5T_NATIVE_INT, {}, &value);
}

void write_attribute(hid_t object, const std::string& name, long long value)
{
    write_raw_attribute(object, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, {}, &value);
}

void write_attribute(hid_t object, const std::string& name, const std::string& value)
{
    Handle type = string_type();
    const char* pointer = value.c_str();
    write_raw_attribute(object, name, type.id(), type.id(), {}, &pointer);
}

void write_attribute(hid_t object, const std::string& name, std::span<const double> values)
{
    write_raw_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {static_cast<hsize_t>(values.size())},
                        values.data());
}

// --- reading -----------------------------------------------------------------

std::size_t Array::n_values() const
{
    switch (type) {
    case Type::real:
        return reals.size();
    case Type::integer:
        return integers.size();
    case Type::string:
        return strings.size();
    default:
        return static_cast<std::size_t>(product(dims));
    }
}

std::string format_dims(const std::vector<hsize_t>& dims)
{
    std::string out = "(";
    for (std::size_t i = 0; i < dims.size(); ++i)
        out += (i > 0 ? ", " : "") + std::to_string(dims[i]);
    return out + ")";
}

namespace {

// Reads a dataset or an attribute (read(memory_type, buffer) does the H5Dread/H5Aread).
template <class Read>
Array read_array(hid_t file_type, hid_t space, const std::string& what, Read read)
{
    Array out;
    const int rank = H5Sget_simple_extent_ndims(space);
    if (rank < 0)
        throw_error(what);
    out.dims.resize(static_cast<std::size_t>(rank));
    if (rank > 0 && H5Sget_simple_extent_dims(space, out.dims.data(), nullptr) < 0)
        throw_error(what);
    const hssize_t n_points = H5Sget_simple_extent_npoints(space);
    if (n_points < 0)
        throw_error(what);
    const auto n = static_cast<std::size_t>(n_points);

    const H5T_class_t type_class = H5Tget_class(file_type);
    const std::size_t size = H5Tget_size(file_type);
    if (type_class == H5T_FLOAT) {
        out.type = Array::Type::real;
        out.type_description = "float" + std::to_string(8 * size);
        out.reals.resize(n);
        if (n > 0 && read(H5T_NATIVE_DOUBLE, out.reals.data()) < 0)
            throw_error(what);
    } else if (type_class == H5T_INTEGER) {
        out.type = Array::Type::integer;
        out.type_description =
            (H5Tget_sign(file_type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(8 * size);
        out.integers.resize(n);
        if (n > 0 && read(H5T_NATIVE_LLONG, out.integers.data()) < 0)
            throw_error(what);
    } else if (type_class == H5T_STRING) {
        out.type = Array::Type::string;
        out.type_description = "string";
        const htri_t variable = H5Tis_variable_str(file_type);
        if (variable < 0)
            throw_error(what);
        Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose, what);
        H5Tset_cset(memory_type.id(), H5Tget_cset(file_type));
        if (variable > 0) {
            H5Tset_size(memory_type.id(), H5T_VARIABLE);
            std::vector<char*> pointers(n, nullptr);
            if (n > 0 && read(memory_type.id(), pointers.data()) < 0)
                throw_error(what);
            for (char* pointer : pointers) {
                out.strings.emplace_back(pointer != nullptr ? pointer : "");
                H5free_memory(pointer);
            }
        } else {
            H5Tset_size(memory_type.id(), size);
            std::vector<char> buffer(n * size);
            if (n > 0 && read(memory_type.id(), buffer.data()) < 0)
                throw_error(what);
            for (std::size_t i = 0; i < n; ++i) {
                const char* begin = buffer.data() + i * size;
                out.strings.emplace_back(begin, std::find(begin, begin + size, '\0'));
            }
        }
    } else {
        out.type = Array::Type::other;
        out.type_description = "HDF5 type class " + std::to_string(static_cast<int>(type_class));
    }
    return out;
}

}  // namespace

Array read_dataset(hid_t location, const std::string& path)
{
    const std::string what = "cannot read dataset " + object_name(location, path);
    Handle set(H5Dopen2(location, path.c_str(), H5P_DEFAULT), H5Dclose, what);
    Handle type(H5Dget_type(set.id()), H5Tclose, what);
    Handle space(H5Dget_space(set.id()), H5Sclose, what);
    return read_array(type.id(), space.id(), what, [&](hid_t memory_type, void* buffer) {
        return H5Dread(set.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
    });
}

Array read_attribute(hid_t object, const std::string& name)
{
    const std::string what = "cannot read attribute " + object_name(object, "") + "@" + name;
    Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose, what);
    Handle type(H5Aget_type(attribute.id()), H5Tclose, what);
    Handle space(H5Aget_space(attribute.id()), H5Sclose, what);
    return read_array(type.id(), space.id(), what,
                      [&](hid_t memory_type, void* buffer) { return H5Aread(attribute.id(), memory_type, buffer); });
}

}  // namespace iga::io::h5
