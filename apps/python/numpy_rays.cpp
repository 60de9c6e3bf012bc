#include "apps/python/numpy_rays.h"

#include "apps/python/bindings.h"
#include "framework/core/error.h"
#include "framework/io/ray_file.h"

#include <fmt/core.h>
#include <pybind11/stl/filesystem.h>

#include <limits>
#include <string>

namespace py = pybind11;

namespace bvhlab {
namespace {

std::string text(const py::handle& object) { return py::str(object).cast<std::string>(); }

// `object` as a NumPy array of float32 or float64 in native byte order, of any strides, of shape
// (N, columns) (columns 0: (N,)), and N == rows when rows >= 0. Else InputError.
py::array checkedFloats(const py::handle& object, const std::string& name, py::ssize_t rows, int columns) {
    const std::string shape = columns ? fmt::format("(N, {})", columns) : "(N,)";
    if (!py::isinstance<py::array>(object))
        throw InputError(
            fmt::format("{}: expected a NumPy array of shape {}, got {}", name, shape, text(py::type::of(object))));
    const auto array = py::reinterpret_borrow<py::array>(object);
    const py::dtype dtype = array.dtype();
    if (dtype.kind() != 'f' || (dtype.itemsize() != 4 && dtype.itemsize() != 8) || !dtype.attr("isnative").cast<bool>())
        throw InputError(fmt::format("{}: expected float32 or float64, got {}", name, text(dtype)));
    if (array.ndim() != (columns ? 2 : 1) || (columns && array.shape(1) != columns))
        throw InputError(fmt::format("{}: expected shape {}, got {}", name, shape, text(array.attr("shape"))));
    if (rows >= 0 && array.shape(0) != rows)
        throw InputError(fmt::format("{}: {} rows where origins has {}", name, array.shape(0), rows));
    return array;
}

py::array_t<float> floatArray(size_t rows, size_t columns) {
    return columns ? py::array_t<float>({rows, columns}) : py::array_t<float>(rows);
}

}  // namespace

RayArrays::Values RayArrays::valuesOf(py::array array) {
    Values values;
    values.data = static_cast<const char*>(array.data());
    values.rowStride = array.strides(0);
    values.columnStride = array.ndim() > 1 ? array.strides(1) : 0;
    values.isDouble = array.itemsize() == 8;
    values.array = std::move(array);
    return values;
}

RayArrays::Values RayArrays::intervalOf(const py::handle& object, const std::string& name, size_t n) {
    if (py::isinstance<py::array>(object) && py::reinterpret_borrow<py::array>(object).ndim() > 0)
        return valuesOf(checkedFloats(object, name, py::ssize_t(n), 0));
    Values values;
    try {
        values.constant = py::cast<float>(object);
    } catch (const py::cast_error&) {
        throw InputError(
            fmt::format("{}: expected a number or an (N,) float array, got {}", name, text(py::type::of(object))));
    }
    return values;
}

RayArrays::RayArrays(const py::handle& origins, const py::handle& directions, const py::handle& tmin,
                     const py::handle& tmax) {
    origins_ = valuesOf(checkedFloats(origins, "origins", -1, 3));
    size_ = size_t(origins_.array.shape(0));
    directions_ = valuesOf(checkedFloats(directions, "directions", py::ssize_t(size_), 3));
    tmin_ = intervalOf(tmin, "tmin", size_);
    tmax_ = intervalOf(tmax, "tmax", size_);
}

void RayArrays::read(size_t begin, std::span<Ray> out) const {
    for (size_t k = 0; k < out.size(); ++k) {
        const size_t i = begin + k;
        out[k].org = {origins_(i, 0), origins_(i, 1), origins_(i, 2)};
        out[k].dir = {directions_(i, 0), directions_(i, 1), directions_(i, 2)};
        out[k].tmin = tmin_(i);
        out[k].tmax = tmax_(i);
    }
}

std::vector<Ray> RayArrays::all() const {
    std::vector<Ray> rays(size_);
    read(0, rays);
    return rays;
}

py::dict raysToArrays(const std::vector<Ray>& rays) {
    py::array_t<float> origins = floatArray(rays.size(), 3), directions = floatArray(rays.size(), 3);
    py::array_t<float> tmin = floatArray(rays.size(), 0), tmax = floatArray(rays.size(), 0);
    float *o = origins.mutable_data(), *d = directions.mutable_data();
    for (size_t i = 0; i < rays.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            o[3 * i + k] = rays[i].org[k];
            d[3 * i + k] = rays[i].dir[k];
        }
        tmin.mutable_data()[i] = rays[i].tmin;
        tmax.mutable_data()[i] = rays[i].tmax;
    }
    py::dict arrays;
    arrays["origins"] = origins;
    arrays["directions"] = directions;
    arrays["tmin"] = tmin;
    arrays["tmax"] = tmax;
    return arrays;
}

py::array hitsToArray(const std::vector<Hit>& hits) {
    py::array_t<HitRecord> array(py::ssize_t(hits.size()));
    writeHitRecords<HitRecord>(hits, {}, array.mutable_data());
    return array;
}

std::vector<Hit> hitsFromArray(const py::handle& object) {
    if (!py::isinstance<py::array>(object) || py::reinterpret_borrow<py::array>(object).dtype().attr("names").is_none())
        throw InputError(
            "hits: expected a NumPy structured array with fields t, prim, u, v (as accel.intersect returns)");
    const auto array = py::reinterpret_borrow<py::array>(object);
    const auto names = array.dtype().attr("names").cast<py::tuple>();
    auto field = [&]<typename T>(const char* name, T) {
        if (!names.contains(name)) throw InputError(fmt::format("hits: no field '{}' (fields t, prim, u, v)", name));
        return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(py::object(array[py::str(name)]));
    };
    const auto t = field("t", 0.0f), u = field("u", 0.0f), v = field("v", 0.0f);
    const auto prim = field("prim", int64_t(0));
    if (array.ndim() != 1) throw InputError("hits: expected one dimension, one record per ray");
    std::vector<Hit> hits(size_t(array.shape(0)));
    for (size_t i = 0; i < hits.size(); ++i) {
        const int64_t p = prim.at(py::ssize_t(i));
        if (p >= int64_t(kInvalidPrimitive)) throw InputError(fmt::format("hits: prim {} out of range", p));
        hits[i] = {t.at(py::ssize_t(i)), p < 0 ? kInvalidPrimitive : uint32_t(p), u.at(py::ssize_t(i)),
                   v.at(py::ssize_t(i))};
    }
    return hits;
}

void bindRayFiles(py::module_& m) {
    m.def(
        "read_rays", [](const std::filesystem::path& file) { return raysToArrays(readRayFile(file)); }, py::arg("path"),
        "The rays of a BVHRAYS1 file as {origins, directions, tmin, tmax}: accel.intersect(**rays).");
    m.def(
        "write_rays",
        [](const std::filesystem::path& file, const py::handle& origins, const py::handle& directions,
           const py::handle& tmin,
           const py::handle& tmax) { writeRayFile(file, RayArrays(origins, directions, tmin, tmax).all()); },
        py::arg("path"), py::arg("origins"), py::arg("directions"), py::arg("tmin") = 0.0f,
        py::arg("tmax") = std::numeric_limits<float>::infinity(),
        "Writes rays as a BVHRAYS1 file (bvhlab raycast --rays).");
    m.def(
        "read_hits", [](const std::filesystem::path& file) { return hitsToArray(readHitFile(file)); }, py::arg("path"),
        "The hits of a BVHHITS1 file (bvhlab raycast --out) as accel.intersect returns them.");
    m.def(
        "write_hits",
        [](const std::filesystem::path& file, const py::handle& hits) { writeHitFile(file, hitsFromArray(hits)); },
        py::arg("path"), py::arg("hits"), "Writes hits (fields t, prim, u, v) as a BVHHITS1 file.");
}

}  // namespace bvhlab
