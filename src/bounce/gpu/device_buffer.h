// DeviceBuffer<T>: an array in GPU memory that owns its allocation. It grows on demand and keeps
// its memory when it shrinks, so buffers resized every frame allocate once. Copies to and from
// the host are explicit (upload, download): transfers stay visible in the code that makes them.
#pragma once

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "bounce/gpu/cuda_check.h"

namespace bounce {

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(size_t n) { resize(n); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept { swap(o); }
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    swap(o);
    return *this;
  }
  ~DeviceBuffer() {
    if (data_) cudaFree(data_);
  }

  // Contents are not kept when the buffer grows.
  void resize(size_t n) {
    if (n > capacity_) {
      if (data_) BOUNCE_CUDA(cudaFree(data_));
      data_ = nullptr;
      capacity_ = 0;
      BOUNCE_CUDA(cudaMalloc(reinterpret_cast<void**>(&data_), n * sizeof(T)));
      capacity_ = n;
    }
    size_ = n;
  }
  void upload(const T* host, size_t n) {
    resize(n);
    if (n) BOUNCE_CUDA(cudaMemcpy(data_, host, n * sizeof(T), cudaMemcpyHostToDevice));
  }
  void upload(std::span<const T> host) { upload(host.data(), host.size()); }
  void upload(const std::vector<T>& host) { upload(host.data(), host.size()); }
  void download(T* host, size_t n) const {
    if (n) BOUNCE_CUDA(cudaMemcpy(host, data_, n * sizeof(T), cudaMemcpyDeviceToHost));
  }
  std::vector<T> download() const {
    std::vector<T> host(size_);
    download(host.data(), size_);
    return host;
  }
  void fill_zero() {
    if (size_) BOUNCE_CUDA(cudaMemsetAsync(data_, 0, size_ * sizeof(T)));
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  size_t size() const { return size_; }
  size_t bytes() const { return capacity_ * sizeof(T); }
  bool empty() const { return size_ == 0; }

 private:
  void swap(DeviceBuffer& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }
  T* data_ = nullptr;
  size_t size_ = 0;
  size_t capacity_ = 0;
};

// The device address of host_element's copy, for an array uploaded as a whole: a view's pointers
// into a host array become pointers into its device copy. Null stays null.
template <typename T>
T* relocate(const T* host_element, std::span<const T> host, const DeviceBuffer<T>& device) {
  if (host_element == nullptr) return nullptr;
  return const_cast<T*>(device.data()) + (host_element - host.data());
}

}  // namespace bounce
