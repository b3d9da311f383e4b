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
, seq INTEGER);
CREATE TABLE jobs (
  id              TEXT PRIMARY KEY,   -- SHA-256 of the canonical scene
  train           TEXT NOT NULL,      -- train name
  speed_kmh       REAL NOT NULL,
  irregularity    TEXT NOT NULL,      -- profile label, 'none' for a perfect track
  operator_key    TEXT NOT NULL,      -- SHA-256 of (structure model, dt, HHT, contact needs): jobs sharing a factorization
  dt_s            REAL NOT NULL,
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
, warnings TEXT, rung TEXT, seq INTEGER, planned_modes INTEGER, scene_part INTEGER, scene_speed TEXT, step_reason INTEGER, fidelity_record INTEGER);
CREATE INDEX jobs_lease ON jobs (state, lease_expires);
CREATE TABLE cache_stats (
  study_id        TEXT PRIMARY KEY REFERENCES studies (id),
  jobs            INTEGER NOT NULL DEFAULT 0,   -- jobs finished (done or failed after a run)
  factorizations  INTEGER NOT NULL DEFAULT 0,
  hits            INTEGER NOT NULL DEFAULT 0,
  factorization_s REAL NOT NULL DEFAULT 0,
  evictions       INTEGER NOT NULL DEFAULT 0
);
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
CREATE UNIQUE INDEX jobs_seq ON jobs (seq);
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
CREATE TABLE static_envelopes (
  structure_job TEXT NOT NULL REFERENCES jobs (id),  -- the job whose scene gives the structure and its rail lines
  train_job     TEXT NOT NULL REFERENCES jobs (id),  -- the job whose scene gives the train's axles
  quantity      TEXT NOT NULL,        -- deck_displacement_m, bending_moment_Nm, shear_force_N, support_reaction_N, support_rotation_rad
  place         INTEGER NOT NULL,     -- the output point's or the support's index in the structure
  location      TEXT NOT NULL,        -- its name
  value         REAL,                 -- max over the train's positions; NULL: the section has no such form
  PRIMARY KEY (structure_job, train_job, quantity, place)
) WITHOUT ROWID;
CREATE TABLE scene_parts (
  part INTEGER PRIMARY KEY,           -- what a job's row holds (jobs.scene_part)
  head TEXT NOT NULL,                 -- the scene up to and with its first "speed_kmh": (all of it when none)
  tail TEXT NOT NULL,                 -- the scene after the speed's number
  UNIQUE (head, tail)
);
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
CREATE INDEX jobs_claim ON jobs (operator_key, rung, train) WHERE state = 'queued';
CREATE TABLE step_reasons (
  number INTEGER PRIMARY KEY,         -- what a job's row holds (jobs.step_reason)
  text   TEXT NOT NULL UNIQUE         -- why the job's dt_s is what it is (the planner's words)
);
CREATE TABLE fidelity_records (
  number INTEGER PRIMARY KEY,         -- what a job's row holds (jobs.fidelity_record)
  id     TEXT NOT NULL UNIQUE,        -- SHA-256 of record
  record TEXT NOT NULL                -- JSON: model, contact law, solver path, DOFs, HHT parameters, modes, ...
);
CREATE VIEW job_records AS
  SELECT j.id, j.train, j.speed_kmh, j.irregularity, j.operator_key, j.dt_s, r.text AS dt_reason, j.cutoff_hz, j.state,
    j.attempts, j.max_attempts, j.worker, j.lease_expires, j.error, j.status, j.steps, j.wall_s, j.loop_s, j.setup_s,
    j.factorization_s, j.enqueued_at, j.started_at, j.finished_at, j.warnings, j.rung, f.id AS fidelity_id, j.seq,
    j.planned_modes, j.scene_part, j.scene_speed, p.head || j.scene_speed || p.tail AS scene, f.record AS fidelity
  FROM jobs j LEFT JOIN scene_parts p ON p.part = j.scene_part LEFT JOIN step_reasons r ON r.number = j.step_reason
  LEFT JOIN fidelity_records f ON f.number = j.fidelity_record;
)sql";
  return kSql;
}

}  // namespace railvsi::scheduler
