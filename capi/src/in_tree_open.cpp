#include "capi/src/in_tree_open.hpp"

#include <new>
#include <utility>

#include "capi/src/error_detail.hpp"
#include "capi/src/tables_handle.hpp"

namespace spread::capi {

spread_status open_contents(tables::TableContents contents, spread_tables** out_tables) {
  if (out_tables == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "open_contents: out_tables is NULL");
  *out_tables = nullptr;
  const spread_allocator& a = default_allocator();
  void* storage = a.alloc(a.user, sizeof(spread_tables), alignof(spread_tables));
  if (storage == nullptr) return fail(SPREAD_ERROR_OUT_OF_MEMORY, "open_contents: out of memory");
  try {
    *out_tables = new (storage) spread_tables(std::move(contents), a);
    return SPREAD_OK;
  } catch (const tables::TableError& e) {
    a.free(a.user, storage, sizeof(spread_tables));
    return fail(e.kind() == tables::TableErrorKind::kEmpty ? SPREAD_ERROR_FILE_EMPTY : SPREAD_ERROR_FILE_CORRUPT, "%s",
                e.what());
  } catch (const std::bad_alloc&) {
    a.free(a.user, storage, sizeof(spread_tables));
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "open_contents: out of memory");
  } catch (const std::exception& e) {
    a.free(a.user, storage, sizeof(spread_tables));
    return fail(SPREAD_ERROR_INTERNAL, "open_contents: %s", e.what());
  }
}

}  // namespace spread::capi
