#include "store/store_schema.hpp"

#include <sqlite3.h>

#include <string_view>

#include "core/sha256.hpp"
#include "core/unix_time.hpp"
#include "store/fresh_store_schema.hpp"

#include <stdexcept>
#include <vector>

#include <fmt/format.h>

namespace railvsi::scheduler {
namespace {

struct Migration {
  const char* description;
  const char* sql;
};

// Never edit a released migration: add a new one.
const std::vector<Migration>& migrations() {
  static const std::vector<Migration> all = {
      {"studies, jobs, study_jobs, envelopes, cache_stats; views study_envelopes and study_progress",
       R"sql(
CREATE TABLE studies (
  id           TEXT PRIMARY KEY,      -- SHA-256 of the canonical study document
  name         TEXT NOT NULL,         -- "name" of the study, else the file name
  file         TEXT NOT NULL,         -- the study file as submitted
  document     TEXT NOT NULL,         -- canonical JSON of the study
  checks       TEXT NOT NULL,         -- JSON object of the study's "checks"
  job_count    INTEGER NOT NULL,
  submitted_at REAL NOT NULL          -- Unix time, s
);
CREATE TABLE jobs (
  id              TEXT PRIMARY KEY,   -- SHA-256 of the canonical scene
  scene           TEXT NOT NULL,      -- canonical scene JSON (what the worker runs)
  train           TEXT NOT NULL,      -- train name
  speed_kmh       REAL NOT NULL,
  irregularity    TEXT NOT NULL,      -- profile label, 'none' for a perfect track
  operator_key    TEXT NOT NULL,      -- SHA-256 of (structure model, dt, HHT, contact needs): jobs sharing a factorization
  dt_s            REAL NOT NULL,
  dt_reason       TEXT NOT NULL,
  cutoff_hz       REAL NOT NULL,      -- low-pass cut-off of the deck acceleration envelope
  state           TEXT NOT NULL DEFAULT 'queued'
                  CHECK (state IN ('queued', 'running', 'done', 'failed', 'cancelled')),
  attempts        INTEGER NOT NULL DEFAULT 0,
  max_attempts    INTEGER NOT NULL DEFAULT 3,
  worker          TEXT,               -- host:pid:thread of the last claim
  lease_expires   REAL,               -- Unix time, s; a running job past it returns to the queue
  error           TEXT,               -- why the job failed (last attempt)
  status          TEXT,               -- engine status of the run: ok, diverged, no_convergence, invalid_input
  fidelity        TEXT,               -- JSON: model, contact law, solver path, DOFs, HHT parameters
  steps           INTEGER,
  wall_s          REAL,               -- whole job: model, setup, time loop, envelopes
  loop_s          REAL,               -- time loop only
  setup_s         REAL,               -- static equilibrium (and factorization when not shared)
  factorization_s REAL,               -- spent factorizing for this job, 0 on a cache hit
  enqueued_at     REAL NOT NULL,
  started_at      REAL,
  finished_at     REAL
);
CREATE INDEX jobs_claim ON jobs (state, operator_key);
CREATE INDEX jobs_lease ON jobs (state, lease_expires);
CREATE TABLE study_jobs (
  study_id TEXT NOT NULL REFERENCES studies (id),
  job_id   TEXT NOT NULL REFERENCES jobs (id),
  position INTEGER NOT NULL,          -- order of the job in the study: trains, then speeds, then profiles
  PRIMARY KEY (study_id, job_id)
) WITHOUT ROWID;
CREATE INDEX study_jobs_job ON study_jobs (job_id);
CREATE TABLE envelopes (
  job_id   TEXT NOT NULL REFERENCES jobs (id),
  quantity TEXT NOT NULL,             -- e.g. deck_acceleration_mps2 (unit in the name)
  location TEXT NOT NULL,             -- output point, wheel or vehicle name; '' for the whole job
  value    REAL,                      -- NULL when the run could not produce it (never NaN)
  PRIMARY KEY (job_id, quantity, location)
) WITHOUT ROWID;
CREATE TABLE cache_stats (
  study_id        TEXT PRIMARY KEY REFERENCES studies (id),
  jobs            INTEGER NOT NULL DEFAULT 0,   -- jobs finished (done or failed after a run)
  factorizations  INTEGER NOT NULL DEFAULT 0,
  hits            INTEGER NOT NULL DEFAULT 0,
  factorization_s REAL NOT NULL DEFAULT 0,
  evictions       INTEGER NOT NULL DEFAULT 0
);
CREATE VIEW study_envelopes AS
  SELECT sj.study_id, j.id AS job_id, j.train, j.speed_kmh, j.irregularity, e.quantity, e.location, e.value
  FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id JOIN envelopes e ON e.job_id = j.id;
CREATE VIEW study_progress AS
  SELECT sj.study_id, j.state, count(*) AS jobs
  FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id GROUP BY sj.study_id, j.state;
)sql"},
      {"jobs.warnings: run-health warnings of the run (JSON array of {code, message, ...})",
       R"sql(
ALTER TABLE jobs ADD COLUMN warnings TEXT;  -- JSON array; NULL before the run
)sql"},
      {"shard: which shard of a study a shard store is; merged_shards: the shards merged into a store",
       R"sql(
CREATE TABLE shard (                  -- one row in a store written by vsi shard, none elsewhere
  study_id       TEXT PRIMARY KEY REFERENCES studies (id),
  shard_index    INTEGER NOT NULL,    -- 0 .. shard_count - 1 (SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX)
  shard_count    INTEGER NOT NULL,
  estimated_cost REAL NOT NULL,       -- sum over its jobs of steps x model DOFs
  created_at     REAL NOT NULL        -- Unix time, s
);
CREATE TABLE merged_shards (          -- in a store written by vsi merge: the shards merged into it
  study_id        TEXT NOT NULL REFERENCES studies (id),
  shard_index     INTEGER NOT NULL,
  shard_count     INTEGER NOT NULL,
  file            TEXT NOT NULL,      -- the shard file at the last merge
  jobs_done       INTEGER NOT NULL,   -- jobs of the shard done at the last merge
  -- the shard's factorization cache statistics at the last merge; cache_stats
  -- of the study is their sum, so merging again counts nothing twice
  cache_jobs      INTEGER NOT NULL,
  factorizations  INTEGER NOT NULL,
  hits            INTEGER NOT NULL,
  factorization_s REAL NOT NULL,
  evictions       INTEGER NOT NULL,
  merged_at       REAL NOT NULL,
  PRIMARY KEY (study_id, shard_index)
) WITHOUT ROWID;
)sql"},
      {"jobs.rung: the rung planned at submission (moving_forces/modal, interaction/fe, ...); modal jobs of one "
       "structure and train are claimed as one batch",
       R"sql(
ALTER TABLE jobs ADD COLUMN rung TEXT;  -- NULL for jobs submitted before the planner: FE as their analysis says
)sql"},
      {"envelopes.error_estimate and verification_jobs: a study's accuracy.verify re-runs its governing cases "
       "(and a sample) one rung up; each verified envelope value gets the relative difference",
       R"sql(
ALTER TABLE envelopes ADD COLUMN error_estimate REAL;  -- (value - verified) / verified; NULL: not verified
CREATE TABLE verification_jobs (
  study_id      TEXT NOT NULL REFERENCES studies (id),
  job_id        TEXT NOT NULL REFERENCES jobs (id),  -- the study's job verified
  verify_job_id TEXT NOT NULL REFERENCES jobs (id),  -- its re-run, a job of no study
  refinement    INTEGER NOT NULL,                    -- 1: dt/2 on the job's rung; 2: dt/2 on the next rung
  why           TEXT NOT NULL,                       -- e.g. "governing deck_acceleration_mps2", "sample"
  PRIMARY KEY (study_id, job_id, verify_job_id)
) WITHOUT ROWID;
CREATE INDEX verification_jobs_verify ON verification_jobs (verify_job_id);
)sql"},
      {"price_rows: what vsi price --db F --study ID measured for a study's sampled jobs (one row per run of the "
       "ladder and priced quantity), for the report's accuracy-price chart",
       R"sql(
CREATE TABLE price_rows (
  study_id    TEXT NOT NULL REFERENCES studies (id),
  job_id      TEXT NOT NULL REFERENCES jobs (id),  -- the priced job (its stored scene)
  run         INTEGER NOT NULL,     -- index of the run in the job's ladder (rung, then decreasing dt)
  model       TEXT NOT NULL,        -- moving_forces, interaction
  structure   TEXT NOT NULL,        -- fe, modal
  contact_law TEXT NOT NULL,        -- none, rigid, linear-hertz, hertz
  modes       INTEGER,              -- modal rungs: modes kept; NULL for fe
  dt_s        REAL NOT NULL,
  status      TEXT NOT NULL,        -- the run's status, 'refused' when the rung cannot run the scene
  cpu_s       REAL NOT NULL,        -- thread CPU time of the run alone (setup it shares included)
  wall_s      REAL NOT NULL,
  reference   INTEGER NOT NULL,     -- 1 for the run the errors are relative to
  quantity    TEXT NOT NULL,        -- envelope quantity name (overall value)
  value       REAL,                 -- NULL when the run has none
  error       REAL,                 -- signed relative difference to the reference, fraction; NULL when none
  pareto      INTEGER NOT NULL,     -- 1 on the Pareto front of |error| against cpu_s for this quantity
  priced_at   REAL NOT NULL,        -- Unix time, s
  PRIMARY KEY (study_id, job_id, run, quantity)
) WITHOUT ROWID;
)sql"},
      {"jobs_claim indexes (state, operator_key, rung, train): a batch claim (the queued jobs of one structure "
       "and rung) reads its rows from the index, in order of train, instead of every queued row of the structure",
       R"sql(
DROP INDEX jobs_claim;
CREATE INDEX jobs_claim ON jobs (state, operator_key, rung, train);
)sql"},
      {"job_scenes and fidelity_records: the scene (written once) and the fidelity record (one per rung and "
       "structure, shared by its jobs) out of the jobs rows, so that claims and completions rewrite small rows; "
       "view job_records: jobs with their scene and fidelity as before",
       R"sql(
CREATE TABLE job_scenes (
  job_id TEXT PRIMARY KEY REFERENCES jobs (id),
  scene  TEXT NOT NULL                -- canonical scene JSON (what the worker runs); its SHA-256 is job_id
);
INSERT INTO job_scenes (job_id, scene) SELECT id, scene FROM jobs ORDER BY rowid;
CREATE TABLE fidelity_records (
  id     TEXT PRIMARY KEY,            -- SHA-256 of record
  record TEXT NOT NULL                -- JSON: model, contact law, solver path, DOFs, HHT parameters, modes, ...
) WITHOUT ROWID;
INSERT OR IGNORE INTO fidelity_records (id, record)
  SELECT vsi_sha256(fidelity), fidelity FROM jobs WHERE fidelity IS NOT NULL;
-- NULL before the run. No REFERENCES clause: a foreign key on a column that
-- each completion sets makes SQLite keep a statement journal per UPDATE,
-- which cost more than the rest of the completion; the queue writes the
-- record first in the same transaction, and vsi check verifies it.
ALTER TABLE jobs ADD COLUMN fidelity_id TEXT;
UPDATE jobs SET fidelity_id = vsi_sha256(fidelity) WHERE fidelity IS NOT NULL;
ALTER TABLE jobs DROP COLUMN scene;     -- SQLite >= 3.35
ALTER TABLE jobs DROP COLUMN fidelity;
CREATE VIEW job_records AS
  SELECT j.*, s.scene, f.record AS fidelity
  FROM jobs j LEFT JOIN job_scenes s ON s.job_id = j.id LEFT JOIN fidelity_records f ON f.id = j.fidelity_id;
)sql"},
      {"job_envelopes: the envelopes keyed by the job's number in the store (jobs.seq, in the order the jobs "
       "were added) instead of its SHA-256: a batch's results go to neighbouring pages of a table a third the "
       "size, instead of one page per job anywhere in it; view envelopes gives them by job id as before",
       R"sql(
-- Assigned when the row is added (the largest so far + 1). Not the rowid:
-- VACUUM may renumber the rowids of a table without an INTEGER PRIMARY KEY.
ALTER TABLE jobs ADD COLUMN seq INTEGER;
UPDATE jobs SET seq = rowid;
CREATE UNIQUE INDEX jobs_seq ON jobs (seq);
CREATE TABLE job_envelopes (
  job_seq        INTEGER NOT NULL REFERENCES jobs (seq),
  quantity       TEXT NOT NULL,       -- e.g. deck_acceleration_mps2 (unit in the name)
  location       TEXT NOT NULL,       -- output point, wheel or vehicle name; '' for the whole job
  value          REAL,                -- NULL when the run could not produce it (never NaN)
  error_estimate REAL,                -- (value - verified) / verified; NULL: not verified
  PRIMARY KEY (job_seq, quantity, location)
) WITHOUT ROWID;
INSERT INTO job_envelopes (job_seq, quantity, location, value, error_estimate)
  SELECT j.seq, e.quantity, e.location, e.value, e.error_estimate FROM envelopes e JOIN jobs j ON j.id = e.job_id
  ORDER BY j.seq, e.quantity, e.location;
DROP VIEW study_envelopes;
DROP TABLE envelopes;
CREATE VIEW envelopes AS
  SELECT j.id AS job_id, e.quantity, e.location, e.value, e.error_estimate
  FROM job_envelopes e JOIN jobs j ON j.seq = e.job_seq;
CREATE VIEW study_envelopes AS
  SELECT sj.study_id, j.id AS job_id, j.train, j.speed_kmh, j.irregularity, e.quantity, e.location, e.value
  FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id JOIN job_envelopes e ON e.job_seq = j.seq;
)sql"},
      {"jobs.planned_modes: on the modal moving-force rung, the modes the submission counted up to the cut-off, "
       "so that a worker's modal basis starts at the batch of modes that reaches past it",
       R"sql(
ALTER TABLE jobs ADD COLUMN planned_modes INTEGER;  -- NULL: not counted (FE rungs, jobs of an older vsi)
)sql"},
      {"study_structures: the bridges of a line study (its \"structures\"), one row per bridge a job runs for; a "
       "job stays keyed by its scene, so a bridge that two lines (or two names) share is one job",
       R"sql(
CREATE TABLE study_structures (
  study_id  TEXT NOT NULL REFERENCES studies (id),
  job_id    TEXT NOT NULL REFERENCES jobs (id),
  structure TEXT NOT NULL,            -- name of the bridge in the study
  position  INTEGER NOT NULL,         -- the bridge's place in the study's structures
  PRIMARY KEY (study_id, job_id, structure)
) WITHOUT ROWID;
)sql"},
      {"one spelling of the load model, the schema's: fidelity records and price rows of earlier versions said "
       "\"moving-forces\" where scenes say \"moving_forces\" (a record is keyed by its SHA-256, so it is "
       "written anew and its jobs point to it)",
       R"sql(
CREATE TEMP TABLE respelled AS
  SELECT id AS old_id, replace(record, '"model":"moving-forces"', '"model":"moving_forces"') AS record
  FROM fidelity_records WHERE instr(record, '"model":"moving-forces"') > 0;
INSERT OR IGNORE INTO fidelity_records (id, record) SELECT vsi_sha256(record), record FROM respelled;
UPDATE jobs SET fidelity_id = (SELECT vsi_sha256(r.record) FROM respelled r WHERE r.old_id = jobs.fidelity_id)
  WHERE fidelity_id IN (SELECT old_id FROM respelled);
DELETE FROM fidelity_records WHERE id IN (SELECT old_id FROM respelled);
DROP TABLE respelled;
UPDATE price_rows SET model = 'moving_forces' WHERE model = 'moving-forces';
)sql"},
      {"envelope_values: a job's envelopes as rows of its number, a small key of the quantity and location "
       "(envelope_keys) and the value, about a third of job_envelopes' bytes; job_envelopes is now a view of them, "
       "written through as before",
       R"sql(
CREATE TABLE envelope_keys (
  key      INTEGER PRIMARY KEY,       -- what a job's rows hold instead of the two names
  quantity TEXT NOT NULL,             -- e.g. deck_acceleration_mps2 (unit in the name)
  location TEXT NOT NULL,             -- output point, wheel or vehicle name; '' for the whole job
  UNIQUE (quantity, location)
);
CREATE TABLE envelope_values (
  job_seq        INTEGER NOT NULL REFERENCES jobs (seq),
  key            INTEGER NOT NULL REFERENCES envelope_keys (key),
  value          REAL,                -- NULL when the run could not produce it (never NaN)
  error_estimate REAL,                -- (value - verified) / verified; NULL: not verified
  PRIMARY KEY (job_seq, key)
) WITHOUT ROWID;
INSERT INTO envelope_keys (quantity, location) SELECT DISTINCT quantity, location FROM job_envelopes ORDER BY quantity, location;
INSERT INTO envelope_values (job_seq, key, value, error_estimate)
  SELECT e.job_seq, k.key, e.value, e.error_estimate FROM job_envelopes e
  JOIN envelope_keys k ON k.quantity = e.quantity AND k.location = e.location ORDER BY e.job_seq, k.key;
DROP VIEW study_envelopes;
DROP VIEW envelopes;
DROP TABLE job_envelopes;
CREATE VIEW job_envelopes AS
  SELECT v.job_seq, k.quantity, k.location, v.value, v.error_estimate
  FROM envelope_values v JOIN envelope_keys k ON k.key = v.key;
CREATE TRIGGER job_envelopes_insert INSTEAD OF INSERT ON job_envelopes BEGIN
  INSERT OR IGNORE INTO envelope_keys (quantity, location) VALUES (NEW.quantity, NEW.location);
  INSERT INTO envelope_values (job_seq, key, value, error_estimate)
    SELECT NEW.job_seq, key, NEW.value, NEW.error_estimate FROM envelope_keys
    WHERE quantity = NEW.quantity AND location = NEW.location;
END;
CREATE TRIGGER job_envelopes_update INSTEAD OF UPDATE ON job_envelopes BEGIN
  UPDATE envelope_values SET value = NEW.value, error_estimate = NEW.error_estimate
    WHERE job_seq = OLD.job_seq
      AND key = (SELECT key FROM envelope_keys WHERE quantity = OLD.quantity AND location = OLD.location);
END;
CREATE TRIGGER job_envelopes_delete INSTEAD OF DELETE ON job_envelopes BEGIN
  DELETE FROM envelope_values WHERE job_seq = OLD.job_seq
    AND key = (SELECT key FROM envelope_keys WHERE quantity = OLD.quantity AND location = OLD.location);
END;
CREATE VIEW envelopes AS
  SELECT j.id AS job_id, e.quantity, e.location, e.value, e.error_estimate
  FROM job_envelopes e JOIN jobs j ON j.seq = e.job_seq;
CREATE VIEW study_envelopes AS
  SELECT sj.study_id, j.id AS job_id, j.train, j.speed_kmh, j.irregularity, e.quantity, e.location, e.value
  FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id JOIN job_envelopes e ON e.job_seq = j.seq;
)sql"},
      {"static_envelopes: the static envelopes of a train on a structure (deflection at each output point, section "
       "forces and support values of a beam deck), computed once when the study is submitted and read by vsi "
       "query --line and vsi report instead of the static influence lines again; keyed by the two jobs whose "
       "scenes give the structure and the train. A store of an older vsi gets them on its upgrade",
       R"sql(
CREATE TABLE static_envelopes (
  structure_job TEXT NOT NULL REFERENCES jobs (id),  -- the job whose scene gives the structure and its rail lines
  train_job     TEXT NOT NULL REFERENCES jobs (id),  -- the job whose scene gives the train's axles
  quantity      TEXT NOT NULL,        -- deck_displacement_m, bending_moment_Nm, shear_force_N, support_reaction_N, support_rotation_rad
  place         INTEGER NOT NULL,     -- the output point's or the support's index in the structure
  location      TEXT NOT NULL,        -- its name
  value         REAL,                 -- max over the train's positions; NULL: the section has no such form
  PRIMARY KEY (structure_job, train_job, quantity, place)
) WITHOUT ROWID;
)sql"},
      {"scene_parts, study_job_links, study_bridges, study_bridge_jobs: a job's scene is its part (the text of its "
       "structure, train, profile and step, stored once) around its speed; studies link their jobs and bridges by the "
       "stores' numbers (jobs.seq, studies.seq) instead of SHA-256 texts; jobs_claim holds the queued jobs alone. "
       "Views job_scenes, study_jobs and study_structures give (and take) the rows as the tables did",
       R"sql(
CREATE TABLE scene_parts (
  part INTEGER PRIMARY KEY,           -- what a job's row holds (jobs.scene_part)
  head TEXT NOT NULL,                 -- the scene up to and with its first "speed_kmh": (all of it when none)
  tail TEXT NOT NULL,                 -- the scene after the speed's number
  UNIQUE (head, tail)
);
-- No REFERENCES clause (see migration 8); vsi check verifies it.
ALTER TABLE jobs ADD COLUMN scene_part INTEGER;
ALTER TABLE jobs ADD COLUMN scene_speed TEXT;
CREATE TEMP TABLE scene_split (job_id TEXT PRIMARY KEY, head TEXT, speed TEXT, tail TEXT);
INSERT INTO temp.scene_split (job_id, head, speed, tail)
  SELECT job_id, head, substr(rest, 1, n), substr(rest, n + 1) FROM (
    SELECT job_id, head, rest, CASE WHEN c > 0 AND (b = 0 OR c < b) THEN c WHEN b > 0 THEN b
                                    ELSE length(rest) + 1 END - 1 AS n FROM (
      SELECT job_id, head, rest, instr(rest, ',') AS c, instr(rest, '}') AS b FROM (
        SELECT job_id, CASE WHEN i > 0 THEN substr(scene, 1, i + 11) ELSE scene END AS head,
               CASE WHEN i > 0 THEN substr(scene, i + 12) ELSE '' END AS rest
        FROM (SELECT job_id, scene, instr(scene, '"speed_kmh":') AS i FROM job_scenes))))
  ORDER BY job_id;
INSERT OR IGNORE INTO scene_parts (head, tail) SELECT s.head, s.tail FROM temp.scene_split s JOIN jobs j ON j.id = s.job_id ORDER BY j.seq;
UPDATE jobs SET scene_part = p.part, scene_speed = s.speed FROM temp.scene_split s JOIN scene_parts p ON p.head = s.head AND p.tail = s.tail
  WHERE s.job_id = jobs.id;
DROP TABLE temp.scene_split;
DROP VIEW job_records;
DROP TABLE job_scenes;
CREATE VIEW job_scenes AS
  SELECT j.id AS job_id, p.head || j.scene_speed || p.tail AS scene FROM jobs j JOIN scene_parts p ON p.part = j.scene_part;
CREATE TRIGGER job_scenes_insert INSTEAD OF INSERT ON job_scenes BEGIN
  INSERT OR IGNORE INTO scene_parts (head, tail) SELECT head, tail FROM (
    SELECT head, substr(rest, CASE WHEN c > 0 AND (b = 0 OR c < b) THEN c WHEN b > 0 THEN b ELSE length(rest) + 1 END) AS tail FROM (
      SELECT head, rest, instr(rest, ',') AS c, instr(rest, '}') AS b FROM (
        SELECT CASE WHEN i > 0 THEN substr(NEW.scene, 1, i + 11) ELSE NEW.scene END AS head,
               CASE WHEN i > 0 THEN substr(NEW.scene, i + 12) ELSE '' END AS rest
        FROM (SELECT instr(NEW.scene, '"speed_kmh":') AS i))));
  UPDATE jobs SET scene_part = p.part, scene_speed = s.speed FROM (
    SELECT head, substr(rest, 1, n) AS speed, substr(rest, n + 1) AS tail FROM (
      SELECT head, rest, CASE WHEN c > 0 AND (b = 0 OR c < b) THEN c WHEN b > 0 THEN b ELSE length(rest) + 1 END - 1 AS n FROM (
        SELECT head, rest, instr(rest, ',') AS c, instr(rest, '}') AS b FROM (
          SELECT CASE WHEN i > 0 THEN substr(NEW.scene, 1, i + 11) ELSE NEW.scene END AS head,
                 CASE WHEN i > 0 THEN substr(NEW.scene, i + 12) ELSE '' END AS rest
          FROM (SELECT instr(NEW.scene, '"speed_kmh":') AS i))))) s
    JOIN scene_parts p ON p.head = s.head AND p.tail = s.tail
  WHERE jobs.id = NEW.job_id AND jobs.scene_part IS NULL;
END;
CREATE VIEW job_records AS
  SELECT j.*, p.head || j.scene_speed || p.tail AS scene, f.record AS fidelity
  FROM jobs j LEFT JOIN scene_parts p ON p.part = j.scene_part LEFT JOIN fidelity_records f ON f.id = j.fidelity_id;
ALTER TABLE studies ADD COLUMN seq INTEGER;
UPDATE studies SET seq = rowid;
CREATE UNIQUE INDEX studies_seq ON studies (seq);
CREATE TRIGGER studies_number AFTER INSERT ON studies WHEN NEW.seq IS NULL BEGIN
  UPDATE studies SET seq = (SELECT coalesce(max(seq), 0) + 1 FROM studies) WHERE id = NEW.id;
END;
CREATE TABLE study_job_links (
  study_seq INTEGER NOT NULL REFERENCES studies (seq),
  job_seq   INTEGER NOT NULL REFERENCES jobs (seq),
  position  INTEGER NOT NULL,         -- order of the job in the study: trains, then speeds, then profiles
  PRIMARY KEY (study_seq, job_seq)
) WITHOUT ROWID;
INSERT INTO study_job_links (study_seq, job_seq, position)
  SELECT s.seq, j.seq, sj.position FROM study_jobs sj JOIN studies s ON s.id = sj.study_id JOIN jobs j ON j.id = sj.job_id
  ORDER BY s.seq, j.seq;
CREATE INDEX study_job_links_job ON study_job_links (job_seq);
CREATE TABLE study_bridges (
  study_seq INTEGER NOT NULL REFERENCES studies (seq),
  position  INTEGER NOT NULL,         -- the bridge's place in the study's structures
  name      TEXT NOT NULL,            -- name of the bridge in the study
  PRIMARY KEY (study_seq, position)
) WITHOUT ROWID;
CREATE TABLE study_bridge_jobs (
  study_seq INTEGER NOT NULL,
  job_seq   INTEGER NOT NULL REFERENCES jobs (seq),
  position  INTEGER NOT NULL,
  PRIMARY KEY (study_seq, job_seq, position),
  FOREIGN KEY (study_seq, position) REFERENCES study_bridges (study_seq, position)
) WITHOUT ROWID;
INSERT OR IGNORE INTO study_bridges (study_seq, position, name)
  SELECT s.seq, ss.position, ss.structure FROM study_structures ss JOIN studies s ON s.id = ss.study_id
  ORDER BY s.seq, ss.position;
INSERT OR IGNORE INTO study_bridge_jobs (study_seq, job_seq, position)
  SELECT s.seq, j.seq, ss.position FROM study_structures ss JOIN studies s ON s.id = ss.study_id
  JOIN jobs j ON j.id = ss.job_id ORDER BY s.seq, j.seq, ss.position;
DROP VIEW study_progress;
DROP VIEW study_envelopes;
DROP TABLE study_jobs;
DROP TABLE study_structures;
CREATE VIEW study_jobs AS
  SELECT s.id AS study_id, j.id AS job_id, l.position
  FROM study_job_links l JOIN studies s ON s.seq = l.study_seq JOIN jobs j ON j.seq = l.job_seq;
CREATE TRIGGER study_jobs_insert INSTEAD OF INSERT ON study_jobs BEGIN
  SELECT RAISE(ABORT, 'FOREIGN KEY constraint failed') WHERE NOT EXISTS (SELECT 1 FROM studies WHERE id = NEW.study_id)
    OR NOT EXISTS (SELECT 1 FROM jobs WHERE id = NEW.job_id);
  INSERT INTO study_job_links (study_seq, job_seq, position)
    SELECT s.seq, j.seq, NEW.position FROM studies s, jobs j WHERE s.id = NEW.study_id AND j.id = NEW.job_id;
END;
CREATE TRIGGER study_jobs_delete INSTEAD OF DELETE ON study_jobs BEGIN
  DELETE FROM study_job_links WHERE study_seq = (SELECT seq FROM studies WHERE id = OLD.study_id)
    AND job_seq = (SELECT seq FROM jobs WHERE id = OLD.job_id);
END;
CREATE VIEW study_structures AS
  SELECT s.id AS study_id, j.id AS job_id, b.name AS structure, l.position
  FROM study_bridge_jobs l JOIN study_bridges b ON b.study_seq = l.study_seq AND b.position = l.position
  JOIN studies s ON s.seq = l.study_seq JOIN jobs j ON j.seq = l.job_seq;
CREATE TRIGGER study_structures_insert INSTEAD OF INSERT ON study_structures BEGIN
  SELECT RAISE(ABORT, 'FOREIGN KEY constraint failed') WHERE NOT EXISTS (SELECT 1 FROM studies WHERE id = NEW.study_id)
    OR NOT EXISTS (SELECT 1 FROM jobs WHERE id = NEW.job_id);
  INSERT OR IGNORE INTO study_bridges (study_seq, position, name)
    SELECT seq, NEW.position, NEW.structure FROM studies WHERE id = NEW.study_id;
  INSERT INTO study_bridge_jobs (study_seq, job_seq, position)
    SELECT s.seq, j.seq, NEW.position FROM studies s, jobs j WHERE s.id = NEW.study_id AND j.id = NEW.job_id;
END;
CREATE VIEW study_progress AS
  SELECT s.id AS study_id, j.state, count(*) AS jobs
  FROM study_job_links l JOIN studies s ON s.seq = l.study_seq JOIN jobs j ON j.seq = l.job_seq GROUP BY s.id, j.state;
CREATE VIEW study_envelopes AS
  SELECT s.id AS study_id, j.id AS job_id, j.train, j.speed_kmh, j.irregularity, e.quantity, e.location, e.value
  FROM study_job_links l JOIN studies s ON s.seq = l.study_seq JOIN jobs j ON j.seq = l.job_seq
  JOIN job_envelopes e ON e.job_seq = j.seq;
-- Only the queued jobs are claimed by it: at the end of a run it is empty.
DROP INDEX jobs_claim;
CREATE INDEX jobs_claim ON jobs (operator_key, rung, train) WHERE state = 'queued';
)sql"},
      {"step_reasons and numbered fidelity_records: the step's reason and the fidelity record's id, the same for "
       "every job of a structure (or a batch), out of the jobs rows as numbers of rows stored once, as the scenes' "
       "parts are; view job_records gives dt_reason and fidelity_id as before",
       R"sql(
CREATE TABLE step_reasons (
  number INTEGER PRIMARY KEY,         -- what a job's row holds (jobs.step_reason)
  text   TEXT NOT NULL UNIQUE         -- why the job's dt_s is what it is (the planner's words)
);
INSERT OR IGNORE INTO step_reasons (text) SELECT dt_reason FROM jobs ORDER BY seq;
DROP VIEW job_records;
ALTER TABLE fidelity_records RENAME TO fidelity_records_15;
CREATE TABLE fidelity_records (
  number INTEGER PRIMARY KEY,         -- what a job's row holds (jobs.fidelity_record)
  id     TEXT NOT NULL UNIQUE,        -- SHA-256 of record
  record TEXT NOT NULL                -- JSON: model, contact law, solver path, DOFs, HHT parameters, modes, ...
);
INSERT INTO fidelity_records (id, record) SELECT id, record FROM fidelity_records_15 ORDER BY id;
DROP TABLE fidelity_records_15;
-- No REFERENCES clauses, as for fidelity_id before (migration 8); vsi check
-- verifies both.
ALTER TABLE jobs ADD COLUMN step_reason INTEGER;      -- step_reasons.number
ALTER TABLE jobs ADD COLUMN fidelity_record INTEGER;  -- fidelity_records.number; NULL before the run
UPDATE jobs SET step_reason = (SELECT number FROM step_reasons WHERE text = jobs.dt_reason),
  fidelity_record = (SELECT number FROM fidelity_records WHERE id = jobs.fidelity_id);
ALTER TABLE jobs DROP COLUMN dt_reason;
ALTER TABLE jobs DROP COLUMN fidelity_id;
CREATE VIEW job_records AS
  SELECT j.id, j.train, j.speed_kmh, j.irregularity, j.operator_key, j.dt_s, r.text AS dt_reason, j.cutoff_hz, j.state,
    j.attempts, j.max_attempts, j.worker, j.lease_expires, j.error, j.status, j.steps, j.wall_s, j.loop_s, j.setup_s,
    j.factorization_s, j.enqueued_at, j.started_at, j.finished_at, j.warnings, j.rung, f.id AS fidelity_id, j.seq,
    j.planned_modes, j.scene_part, j.scene_speed, p.head || j.scene_speed || p.tail AS scene, f.record AS fidelity
  FROM jobs j LEFT JOIN scene_parts p ON p.part = j.scene_part LEFT JOIN step_reasons r ON r.number = j.step_reason
  LEFT JOIN fidelity_records f ON f.number = j.fidelity_record;
)sql"},
  };
  return all;
}

// vsi_sha256(text): the hex SHA-256 of a text (NULL for NULL), for
// migrations that key rows by content.
void sha256_function(sqlite3_context* context, int, sqlite3_value** args) {
  if (sqlite3_value_type(args[0]) == SQLITE_NULL) {
    sqlite3_result_null(context);
    return;
  }
  const auto* text = reinterpret_cast<const char*>(sqlite3_value_text(args[0]));
  const std::string hex =
      sha256_hex(std::string_view(text, static_cast<std::size_t>(sqlite3_value_bytes(args[0]))));
  sqlite3_result_text(context, hex.data(), static_cast<int>(hex.size()), SQLITE_TRANSIENT);
}

int user_version(Database& db) {
  Statement s = db.prepare("PRAGMA user_version");
  s.step();
  return static_cast<int>(s.int64(0));
}

}  // namespace

void require_vsi_or_empty(Database& db) {
  const int version = user_version(db);
  // schema_version alone (user_version 0): a first migration that was
  // interrupted. A version without vsi's jobs table is another program's
  // (many set user_version).
  Statement s = db.prepare("SELECT group_concat(name, ', '), sum(name = 'schema_version'), sum(name = 'jobs') "
                           "FROM sqlite_schema WHERE type = 'table'");
  if (!s.step() || s.is_null(0)) return;  // no table: a new file
  const bool ours = version == 0 ? s.int64(1) > 0 : s.int64(2) > 0 && s.int64(1) > 0;
  if (!ours)
    throw std::runtime_error(fmt::format("{} is an SQLite database of another program (tables {}; no vsi schema): "
                                         "vsi writes nothing into it; give a new file or a vsi study database",
                                         db.file(), s.text(0)));
}

void require_current_schema(Database& db) {
  const int version = user_version(db);
  if (version == kStoreSchemaVersion) return;
  if (version == 0) throw std::runtime_error(fmt::format("{} is not a vsi study database (it has no vsi schema)", db.file()));
  if (version > kStoreSchemaVersion)
    throw std::runtime_error(fmt::format("{} has schema version {}; this vsi knows up to {}: use a newer vsi",
                                         db.file(), version, kStoreSchemaVersion));
  throw std::runtime_error(fmt::format("{} has schema version {}, older than this vsi's {}; a writing command "
                                       "(vsi work, vsi submit) upgrades it",
                                       db.file(), version, kStoreSchemaVersion));
}

void migrate(Database& db, int up_to_version) {
  static_assert(kStoreSchemaVersion > 0);
  require_vsi_or_empty(db);
  if (migrations().size() != static_cast<std::size_t>(kStoreSchemaVersion))
    throw std::logic_error("kStoreSchemaVersion does not match the migrations");
  if (up_to_version < 1 || up_to_version > kStoreSchemaVersion) throw std::logic_error("migrate: no such version");
  if (user_version(db) >= up_to_version && user_version(db) <= kStoreSchemaVersion) return;
  if (const int rc = sqlite3_create_function_v2(db.handle(), "vsi_sha256", 1, SQLITE_UTF8 | SQLITE_DETERMINISTIC,
                                                nullptr, sha256_function, nullptr, nullptr, nullptr);
      rc != SQLITE_OK)
    throw SqliteError(rc, "sqlite: cannot register vsi_sha256");
  Transaction tx(db);
  const int version = user_version(db);  // again, under the write lock
  if (version > kStoreSchemaVersion)
    throw std::runtime_error(fmt::format("{} has schema version {}; this vsi knows up to {}: use a newer vsi",
                                         db.file(), version, kStoreSchemaVersion));
  // A new, empty file up to the latest version: its schema in one step
  // (fresh_store_schema.hpp), recorded as every migration applied.
  const bool fresh = version == 0 && up_to_version == kStoreSchemaVersion && [&] {
    Statement s = db.prepare("SELECT count(*) FROM sqlite_schema");
    return s.step() && s.int64(0) == 0;
  }();
  if (fresh) db.exec(std::string(fresh_store_schema_sql()));
  else if (version == 0)
    db.exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER PRIMARY KEY, applied_at REAL NOT NULL, "
            "description TEXT NOT NULL)");
  for (int v = version; v < up_to_version; ++v) {
    const Migration& m = migrations()[static_cast<std::size_t>(v)];
    if (!fresh) db.exec(m.sql);
    db.prepare("INSERT INTO schema_version (version, applied_at, description) VALUES (?, ?, ?)")
        .bind(1, v + 1)
        .bind(2, unix_now_s())
        .bind(3, m.description)
        .run();
  }
  // PRAGMA takes no parameters; the value is our own integer.
  if (up_to_version > version) db.exec(fmt::format("PRAGMA user_version = {}", up_to_version));
  tx.commit();
}

}  // namespace railvsi::scheduler
