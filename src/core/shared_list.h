// A vector whose copies share one buffer until one of them is changed (copy on
// write): the scene's meshes, so every job of a batch or a sweep holds its own
// Scene, with its own settings, over one loaded copy of the geometry.
#pragma once
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace penumbra {

template <class T>
class SharedList {
 public:
  SharedList() = default;
  SharedList(std::vector<T> items) : items_(std::make_shared<std::vector<T>>(std::move(items))) {}

  // Reading never copies.
  const std::vector<T>& items() const { return items_ ? *items_ : none(); }
  operator const std::vector<T>&() const { return items(); }
  size_t size() const { return items().size(); }
  bool empty() const { return items().empty(); }
  const T& operator[](size_t i) const { return items()[i]; }
  const T& back() const { return items().back(); }
  typename std::vector<T>::const_iterator begin() const { return items().begin(); }
  typename std::vector<T>::const_iterator end() const { return items().end(); }
  // Whether two lists read the same buffer (a job's scene and its geometry's).
  bool shares(const SharedList& o) const { return items_ && items_ == o.items_; }

  // Changing detaches first: only the loader and tests change a scene.
  std::vector<T>& edit() {
    if (!items_) items_ = std::make_shared<std::vector<T>>();
    else if (items_.use_count() > 1) items_ = std::make_shared<std::vector<T>>(*items_);
    return *items_;
  }
  T& operator[](size_t i) { return edit()[i]; }
  T& back() { return edit().back(); }
  typename std::vector<T>::iterator begin() { return edit().begin(); }
  typename std::vector<T>::iterator end() { return edit().end(); }
  void push_back(const T& t) { edit().push_back(t); }
  void push_back(T&& t) { edit().push_back(std::move(t)); }
  template <class... Args>
  T& emplace_back(Args&&... args) { return edit().emplace_back(std::forward<Args>(args)...); }
  void reserve(size_t n) { edit().reserve(n); }
  void clear() { edit().clear(); }

 private:
  static const std::vector<T>& none() {
    static const std::vector<T> kNone;
    return kNone;
  }
  std::shared_ptr<std::vector<T>> items_;
};

}  // namespace penumbra
