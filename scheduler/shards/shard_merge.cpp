#include "shards/shard_merge.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/unix_time.hpp"
#include "shards/attached_store.hpp"
#include "shards/shard_store.hpp"
#include "store/store_check.hpp"
#include "store/store_schema.hpp"

namespace railvsi::scheduler {
namespace {

struct CheckedShard {
  std::filesystem::path file;
  ShardMarker marker;
};

CheckedShard check_shard(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw InputError("", "no such shard file", file.string());
  try {
    Database db(file.string());
    // Damage is found here, before the target is touched (a damaged second
    // shard had left the first one merged into a new target).
    try {
      require_sound(db);
    } catch (const std::runtime_error& e) {
      throw InputError("", e.what(), file.string());
    }
    const int version = store_schema_version(db);
    if (version != kStoreSchemaVersion)
      throw InputError("", fmt::format("store schema version {}, this vsi's is {}: merge shards with the vsi that "
                                       "wrote them (or work them with this vsi first, which migrates them)",
                                       version, kStoreSchemaVersion),
                       file.string());
    const auto marker = shard_marker(db);
    if (!marker)
      throw InputError("", "not a shard store (no row in table shard): vsi merge takes the files vsi shard wrote",
                       file.string());
    return {file, *marker};
  } catch (const SqliteError& e) {
    throw InputError("", fmt::format("not a railvsi store: {}", e.what()), file.string());
  }
}

std::string joined(const std::vector<std::string>& names, const char* separator = ", ") {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : separator) + n;
  return out;
}

// One shard into the target, in one transaction. Returns the jobs taken.
std::int64_t merge_one(Database& target, const CheckedShard& shard, const std::string& file_text) {
  const std::string& study = shard.marker.study_id;
  const std::vector<std::string> all_columns = table_columns(target, "main", "jobs");
  AttachedStore attached(target, shard.file, "src");
  if (table_columns(target, "src", "jobs") != all_columns)
    throw InputError("", "its jobs table differs from the target's", shard.file.string());
  // A job's number (seq) is the store's own: the target keeps its numbers
  // and numbers the jobs it takes after its last. So is the number of its
  // scene's part, step reason and fidelity record: the target numbers the
  // ones it takes (below).
  std::vector<std::string> columns;
  std::copy_if(all_columns.begin(), all_columns.end(), std::back_inserter(columns), [](const std::string& c) {
    return c != "seq" && c != "scene_part" && c != "scene_speed" && c != "step_reason" && c != "fidelity_record";
  });
  target.exec("CREATE TEMP TABLE IF NOT EXISTS merge_take (id TEXT PRIMARY KEY)");
  DeferredTransaction tx(target);
  target.exec("DELETE FROM temp.merge_take");
  target.prepare("INSERT OR IGNORE INTO main.studies (id, name, file, document, checks, job_count, submitted_at) "
                 "SELECT id, name, file, document, checks, job_count, submitted_at FROM src.studies WHERE id = ?")
      .bind(1, study)
      .run();
  target.prepare("INSERT OR IGNORE INTO main.cache_stats (study_id) VALUES (?)").bind(1, study).run();
  // Taken: jobs the target lacks, jobs the shard finished that the target
  // has not, and a done result over a failed one.
  target.prepare(
            "INSERT INTO temp.merge_take (id) SELECT s.id FROM src.study_jobs sj JOIN src.jobs s ON s.id = sj.job_id "
            "LEFT JOIN main.jobs m ON m.id = s.id WHERE sj.study_id = ? AND (m.id IS NULL "
            "OR (m.state IN ('queued', 'running') AND s.state IN ('done', 'failed', 'cancelled')) "
            "OR (m.state IN ('failed', 'cancelled') AND s.state = 'done'))")
      .bind(1, study)
      .run();
  std::int64_t taken = 0;
  {
    Statement count = target.prepare("SELECT count(*) FROM temp.merge_take");
    count.step();
    taken = count.int64(0);
  }
  // Column names come from the schema itself, never from user text.
  std::vector<std::string> rest(columns.begin() + 1, columns.end());
  std::vector<std::string> from_source;
  for (const auto& c : rest) from_source.push_back("s." + c);
  // Fidelity records (keyed by content) before the jobs rows that refer to them.
  target.exec("INSERT OR IGNORE INTO main.fidelity_records (id, record) SELECT id, record FROM src.fidelity_records "
              "WHERE number IN (SELECT fidelity_record FROM src.jobs WHERE id IN temp.merge_take) ORDER BY number");
  target.exec("INSERT OR IGNORE INTO main.step_reasons (text) SELECT text FROM src.step_reasons "
              "WHERE number IN (SELECT step_reason FROM src.jobs WHERE id IN temp.merge_take) ORDER BY number");
  target.exec("DELETE FROM main.envelope_values WHERE job_seq IN (SELECT seq FROM main.jobs WHERE id IN temp.merge_take)");
  target.exec(fmt::format("UPDATE main.jobs SET ({}) = (SELECT {} FROM src.jobs s WHERE s.id = main.jobs.id) "
                          "WHERE id IN temp.merge_take",
                          joined(rest), joined(from_source)));
  target.exec(fmt::format("INSERT INTO main.jobs ({0}, seq) SELECT {0}, "
                          "(SELECT coalesce(max(seq), 0) FROM main.jobs) + row_number() OVER (ORDER BY seq) "
                          "FROM src.jobs WHERE id IN temp.merge_take AND id NOT IN (SELECT id FROM main.jobs)",
                          joined(columns)));
  // A taken job's step reason and fidelity record under the target's numbers.
  target.exec("UPDATE main.jobs SET (step_reason, fidelity_record) = (SELECT mr.number, mf.number FROM src.jobs s "
              "LEFT JOIN src.step_reasons sr ON sr.number = s.step_reason LEFT JOIN main.step_reasons mr ON mr.text = sr.text "
              "LEFT JOIN src.fidelity_records sf ON sf.number = s.fidelity_record "
              "LEFT JOIN main.fidelity_records mf ON mf.id = sf.id WHERE s.id = main.jobs.id) WHERE id IN temp.merge_take");
  // A job the shard has not finished waits in the target's queue, not under
  // a lease of a worker on another machine.
  target.exec("UPDATE main.jobs SET state = 'queued', worker = NULL, lease_expires = NULL "
              "WHERE state = 'running' AND id IN temp.merge_take");
  // A taken job's scene, new to the target: its part under the target's
  // number (a set by table, not row by row through the view's trigger).
  target.exec("INSERT OR IGNORE INTO main.scene_parts (head, tail) SELECT head, tail FROM src.scene_parts "
              "WHERE part IN (SELECT scene_part FROM src.jobs WHERE id IN temp.merge_take) ORDER BY part");
  target.exec("UPDATE main.jobs SET (scene_part, scene_speed) = (SELECT mp.part, s.scene_speed FROM src.jobs s "
              "JOIN src.scene_parts sp ON sp.part = s.scene_part JOIN main.scene_parts mp ON mp.head = sp.head "
              "AND mp.tail = sp.tail WHERE s.id = main.jobs.id) WHERE id IN temp.merge_take AND scene_part IS NULL");
  // The envelopes by the target's keys of their quantity and location
  // (a set by table, not row by row through the view's trigger).
  target.exec("INSERT OR IGNORE INTO main.envelope_keys (quantity, location) "
              "SELECT quantity, location FROM src.envelope_keys ORDER BY key");
  target.exec("INSERT INTO main.envelope_values (job_seq, key, value) "
              "SELECT m.seq, mk.key, e.value FROM src.envelope_values e JOIN src.envelope_keys sk ON sk.key = e.key "
              "JOIN main.envelope_keys mk ON mk.quantity = sk.quantity AND mk.location = sk.location "
              "JOIN src.jobs s ON s.seq = e.job_seq JOIN main.jobs m ON m.id = s.id WHERE s.id IN temp.merge_take "
              "ORDER BY m.seq, mk.key");
  target.prepare("INSERT OR IGNORE INTO main.study_jobs (study_id, job_id, position) "
                 "SELECT study_id, job_id, position FROM src.study_jobs WHERE study_id = ?")
      .bind(1, study)
      .run();
  target.prepare("INSERT OR IGNORE INTO main.study_structures (study_id, job_id, structure, position) "
                 "SELECT study_id, job_id, structure, position FROM src.study_structures WHERE study_id = ?")
      .bind(1, study)
      .run();
  // The shard's cache statistics replace those of its last merge; the
  // study's are their sum. Unchanged values write nothing.
  target.prepare(
            "INSERT INTO main.merged_shards (study_id, shard_index, shard_count, file, jobs_done, cache_jobs, "
            "factorizations, hits, factorization_s, evictions, merged_at) "
            "SELECT ?1, ?2, ?3, ?4, (SELECT count(*) FROM src.jobs WHERE state = 'done'), c.jobs, c.factorizations, "
            "c.hits, c.factorization_s, c.evictions, ?5 FROM src.cache_stats c WHERE c.study_id = ?1 "
            "ON CONFLICT (study_id, shard_index) DO UPDATE SET shard_count = excluded.shard_count, file = excluded.file, "
            "jobs_done = excluded.jobs_done, cache_jobs = excluded.cache_jobs, factorizations = excluded.factorizations, "
            "hits = excluded.hits, factorization_s = excluded.factorization_s, evictions = excluded.evictions, "
            "merged_at = excluded.merged_at WHERE (shard_count, file, jobs_done, cache_jobs, factorizations, hits, "
            "factorization_s, evictions) IS NOT (excluded.shard_count, excluded.file, excluded.jobs_done, "
            "excluded.cache_jobs, excluded.factorizations, excluded.hits, excluded.factorization_s, excluded.evictions)")
      .bind(1, study)
      .bind(2, shard.marker.index)
      .bind(3, shard.marker.count)
      .bind(4, file_text)
      .bind(5, unix_now_s())
      .run();
  target.prepare("UPDATE main.cache_stats SET (jobs, factorizations, hits, factorization_s, evictions) = "
                 "(SELECT sum(cache_jobs), sum(factorizations), sum(hits), sum(factorization_s), sum(evictions) "
                 "FROM main.merged_shards WHERE study_id = ?1) WHERE study_id = ?1")
      .bind(1, study)
      .run();
  tx.commit();
  return taken;
}

}  // namespace

MergeSummary merge_shards(const std::vector<std::filesystem::path>& shard_files, const std::filesystem::path& into) {
  if (shard_files.empty()) throw InputError("", "no shard files given", into.string());
  // Every file is checked before anything is written.
  std::vector<CheckedShard> shards;
  std::map<int, std::filesystem::path> by_index;
  for (const auto& f : shard_files) {
    const std::filesystem::path file = std::filesystem::weakly_canonical(f);
    if (std::any_of(shards.begin(), shards.end(), [&](const CheckedShard& s) { return s.file == file; })) continue;
    CheckedShard s = check_shard(file);
    if (!shards.empty()) {
      const ShardMarker& first = shards.front().marker;
      if (s.marker.study_id != first.study_id)
        throw InputError("", fmt::format("a shard of study {}, not of study {} ({}): shards of different studies "
                                         "cannot be merged",
                                         s.marker.study_id, first.study_id, shards.front().file.string()),
                         f.string());
      if (s.marker.count != first.count)
        throw InputError("", fmt::format("shard {} of {}, but {} is a shard of {}: the shards come from different "
                                         "vsi shard runs",
                                         s.marker.index, s.marker.count, shards.front().file.string(), first.count),
                         f.string());
    }
    if (const auto [it, fresh] = by_index.emplace(s.marker.index, file); !fresh)
      throw InputError("", fmt::format("shard {} is given twice (also {})", s.marker.index, it->second.string()),
                       f.string());
    shards.push_back(std::move(s));
  }
  std::sort(shards.begin(), shards.end(),
            [](const CheckedShard& a, const CheckedShard& b) { return a.marker.index < b.marker.index; });

  if (std::filesystem::exists(into) &&
      std::any_of(shards.begin(), shards.end(),
                  [&](const CheckedShard& s) { return s.file == std::filesystem::weakly_canonical(into); }))
    throw InputError("", "the target is one of the shards", into.string());
  Database target(into.string());
  require_sound(target);
  migrate(target);
  if (const auto marker = shard_marker(target))
    throw InputError("", fmt::format("the target is shard {} of {} of a study: merge into a store of its own",
                                     marker->index, marker->count),
                     into.string());

  MergeSummary summary;
  summary.study_id = shards.front().marker.study_id;
  summary.shard_count = shards.front().marker.count;
  for (const CheckedShard& s : shards) {
    MergedShard merged{s.file, s.marker.index, {}, 0};
    merged.new_jobs = merge_one(target, s, s.file.string());
    {
      Database shard_db(s.file.string());
      merged.counts = state_counts(shard_db, summary.study_id);
    }
    summary.new_jobs += merged.new_jobs;
    summary.shards.push_back(std::move(merged));
  }
  for (int k = 0; k < summary.shard_count; ++k)
    if (!by_index.contains(k)) summary.missing.push_back(k);
  summary.target = state_counts(target, summary.study_id);
  Statement name = target.prepare("SELECT name FROM studies WHERE id = ?");
  if (name.bind(1, summary.study_id).step()) summary.study_name = name.text(0);
  return summary;
}

}  // namespace railvsi::scheduler
