#include "store/fresh_store_schema.hpp"

namespace railvsi::scheduler {

std::string_view fresh_store_schema_sql() {
  // Each statement's text is stored as written: keep it byte for byte as
  // the migrations leave it (ALTER TABLE's appended columns included).
  static constexpr std::string_view kSql = R"sql(CREATE TABLE schema_version (version INTEGER PRIMARY KEY, applied_at REAL NOT NULL, description TEXT NOT NULL);
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
  steps           INTEGER,
  wall_s          REAL,               -- whole job: model, setup, time loop, envelopes
  loop_s          REAL,               -- time loop only
  setup_s         REAL,               -- static equilibrium (and factorization when not shared)
  factorization_s REAL,               -- spent factorizing for this job, 0 on a cache hit
  enqueued_at     REAL NOT NULL,
  started_at      REAL,
  finished_at     REAL
, warnings TEXT, rung TEXT, fidelity_id TEXT, seq INTEGER, planned_modes INTEGER);
CREATE INDEX jobs_lease ON jobs (state, lease_expires);
CREATE TABLE study_jobs (
  study_id TEXT NOT NULL REFERENCES studies (id),
  job_id   TEXT NOT NULL REFERENCES jobs (id),
  position INTEGER NOT NULL,          -- order of the job in the study: trains, then speeds, then profiles
  PRIMARY KEY (study_id, job_id)
) WITHOUT ROWID;
CREATE INDEX study_jobs_job ON study_jobs (job_id);
CREATE TABLE cache_stats (
  study_id        TEXT PRIMARY KEY REFERENCES studies (id),
  jobs            INTEGER NOT NULL DEFAULT 0,   -- jobs finished (done or failed after a run)
  factorizations  INTEGER NOT NULL DEFAULT 0,
  hits            INTEGER NOT NULL DEFAULT 0,
  factorization_s REAL NOT NULL DEFAULT 0,
  evictions       INTEGER NOT NULL DEFAULT 0
);
CREATE VIEW study_progress AS
  SELECT sj.study_id, j.state, count(*) AS jobs
  FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id GROUP BY sj.study_id, j.state;
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
CREATE TABLE verification_jobs (
  study_id      TEXT NOT NULL REFERENCES studies (id),
  job_id        TEXT NOT NULL REFERENCES jobs (id),  -- the study's job verified
  verify_job_id TEXT NOT NULL REFERENCES jobs (id),  -- its re-run, a job of no study
  refinement    INTEGER NOT NULL,                    -- 1: dt/2 on the job's rung; 2: dt/2 on the next rung
  why           TEXT NOT NULL,                       -- e.g. "governing deck_acceleration_mps2", "sample"
  PRIMARY KEY (study_id, job_id, verify_job_id)
) WITHOUT ROWID;
CREATE INDEX verification_jobs_verify ON verification_jobs (verify_job_id);
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
CREATE INDEX jobs_claim ON jobs (state, operator_key, rung, train);
CREATE TABLE job_scenes (
  job_id TEXT PRIMARY KEY REFERENCES jobs (id),
  scene  TEXT NOT NULL                -- canonical scene JSON (what the worker runs); its SHA-256 is job_id
);
CREATE TABLE fidelity_records (
  id     TEXT PRIMARY KEY,            -- SHA-256 of record
  record TEXT NOT NULL                -- JSON: model, contact law, solver path, DOFs, HHT parameters, modes, ...
) WITHOUT ROWID;
CREATE VIEW job_records AS
  SELECT j.*, s.scene, f.record AS fidelity
  FROM jobs j LEFT JOIN job_scenes s ON s.job_id = j.id LEFT JOIN fidelity_records f ON f.id = j.fidelity_id;
CREATE UNIQUE INDEX jobs_seq ON jobs (seq);
CREATE TABLE study_structures (
  study_id  TEXT NOT NULL REFERENCES studies (id),
  job_id    TEXT NOT NULL REFERENCES jobs (id),
  structure TEXT NOT NULL,            -- name of the bridge in the study
  position  INTEGER NOT NULL,         -- the bridge's place in the study's structures
  PRIMARY KEY (study_id, job_id, structure)
) WITHOUT ROWID;
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
CREATE TABLE static_envelopes (
  structure_job TEXT NOT NULL REFERENCES jobs (id),  -- the job whose scene gives the structure and its rail lines
  train_job     TEXT NOT NULL REFERENCES jobs (id),  -- the job whose scene gives the train's axles
  quantity      TEXT NOT NULL,        -- deck_displacement_m, bending_moment_Nm, shear_force_N, support_reaction_N, support_rotation_rad
  place         INTEGER NOT NULL,     -- the output point's or the support's index in the structure
  location      TEXT NOT NULL,        -- its name
  value         REAL,                 -- max over the train's positions; NULL: the section has no such form
  PRIMARY KEY (structure_job, train_job, quantity, place)
) WITHOUT ROWID;
)sql";
  return kSql;
}

}  // namespace railvsi::scheduler
