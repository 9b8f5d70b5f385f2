#include "qp/builtins.hpp"

#include <mutex>
#include <vector>

namespace contactqp::detail {
namespace {

// Zero-initialised before any code runs, so lists may be added in any order at load time.
BuiltinList* first_list = nullptr;
bool lists_ran = false;

// Recursive: a registration that a list runs registers through the registries, which call
// register_builtins() again on the same thread (and return at once).
std::recursive_mutex& lists_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

}  // namespace

void add_builtin_list(BuiltinList& list) noexcept {
  std::lock_guard<std::recursive_mutex> lock(lists_mutex());
  list.next = first_list;
  first_list = &list;
  if (lists_ran) list.register_all();
}

void register_builtins() {
  std::lock_guard<std::recursive_mutex> lock(lists_mutex());
  if (lists_ran) return;
  lists_ran = true;
  // The lists were added last first: run them in the order they were added.
  std::vector<BuiltinList*> lists;
  for (BuiltinList* list = first_list; list; list = list->next) lists.insert(lists.begin(), list);
  for (BuiltinList* list : lists) list->register_all();
}

}  // namespace contactqp::detail
