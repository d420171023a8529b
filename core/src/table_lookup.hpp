// The core's method and preset tables: built once, looked up by id.
#pragma once
#include <string>
#include <vector>

namespace tristim {

/// What build() returns, made on the first call and kept for the program's life (the tables
/// behind objective_table(), surface_table(), ...; thread-safe as any function-local static).
template <auto build>
const auto& built_once() {
  static const auto table = build();
  return table;
}

/// The row of `table` whose key_of(row) equals `key`; nullptr when none does.
template <class Row, class Key, class KeyOf>
const Row* find_row(const std::vector<Row>& table, const Key& key, KeyOf key_of) {
  for (const Row& r : table)
    if (key_of(r) == key) return &r;
  return nullptr;
}

/// key_of(row) of every row, ", "-separated: the ids an UnknownId message lists.
template <class Row, class KeyOf>
std::string row_ids(const std::vector<Row>& table, KeyOf key_of) {
  std::string ids;
  for (const Row& r : table) ids += (ids.empty() ? "" : ", ") + key_of(r);
  return ids;
}

}  // namespace tristim
