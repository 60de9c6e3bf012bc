// A view of contiguous elements: a pointer and a count, what std::span is to bvhlab, for the plugin
// API (<span> alone is 16 k lines after the preprocessor). A View is made from anything with
// data() and size() (std::vector, std::span, std::array, a C array), and a std::span is made from
// a View.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <type_traits>

namespace bvhlab {

template <typename T>
class View {
public:
    constexpr View() = default;
    constexpr View(T* data, size_t size) : data_(data), size_(size) {}
    template <typename Container>
    requires requires(Container&& c) {
        static_cast<T*>(c.data());
        size_t(c.size());
    }
    constexpr View(Container&& c) : data_(c.data()), size_(c.size()) {}
    template <size_t N>
    constexpr View(T (&array)[N]) : data_(array), size_(N) {}
    // For arguments written in place, `{a, b}`: the list lives until the call returns. GCC warns
    // that the array may not outlive the View, which is this constructor's contract.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winit-list-lifetime"
#endif
    constexpr View(std::initializer_list<std::remove_const_t<T>> list) requires std::is_const_v<T>
        : data_(list.begin()), size_(list.size()) {}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

    constexpr T* data() const { return data_; }
    constexpr size_t size() const { return size_; }
    constexpr bool empty() const { return size_ == 0; }
    constexpr T& operator[](size_t i) const { return data_[i]; }
    constexpr T& front() const { return data_[0]; }
    constexpr T& back() const { return data_[size_ - 1]; }
    constexpr T* begin() const { return data_; }
    constexpr T* end() const { return data_ + size_; }
    constexpr View first(size_t count) const { return {data_, count}; }
    constexpr View subspan(size_t offset) const { return {data_ + offset, size_ - offset}; }
    constexpr View subspan(size_t offset, size_t count) const { return {data_ + offset, count}; }

private:
    T* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace bvhlab
