#pragma once
// The schema of a new store, created in one step: the same tables, indexes
// and views, with the same text in sqlite_schema, as migrating an empty
// file through every migration in turn (store_schema.cpp), which took 6.5 to
// 9.6 ms against 2.0 to 2.4 ms (the ALTER TABLEs re-read the whole schema).
// A test builds both and compares them entry for entry; a new migration
// fails it until this text is the new result (the test prints it).
#include <string_view>

namespace railvsi::scheduler {

// The SQL of every sqlite_schema entry after the last migration, in order.
std::string_view fresh_store_schema_sql();

}  // namespace railvsi::scheduler
