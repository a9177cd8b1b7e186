#pragma once
// ISO 10303-238 (AP238) programs in the AIM form: Model → the same canonical program, and the
// same program information, as the ISO 14649 (ARM) path gives for the same content.
//
// In:  a Model whose FILE_SCHEMA is INTEGRATED_CNC_SCHEMA, an AttributeReader over its schema
//      (the built-in AP238 AIM subset, schemas/ap238_aim.exp, or any schema that declares the
//      AIM entities with their standard attribute names), and the ARM interpreter's options.
// Out: canonical calls on `sink`, structure markers included (each carries the AIM instance
//      and its entity as written in the file), and diagnostics (AP238-xxx, and the STEPNC-xxx
//      codes of the machinery both interpreters share). What the interpreter does not read is
//      named, never dropped: docs/ap238.md has the mapping as implemented, entity by entity.
//
// The AIM spells each ARM object with generic resources (action methods tied by relationships,
// properties given values by representations); the interpreter follows those links backwards
// through an index built once per call (linear in the model), reads the ARM meaning out of
// them, and drives the same machine (ncpost/stepnc/machine.hpp) as the ARM interpreter.

#include "ncpost/canon/sink.hpp"
#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::ap238 {

// True when the model's FILE_SCHEMA names the AIM (integrated_cnc_schema, any case/version tag).
[[nodiscard]] bool is_aim(const p21::Model& model) noexcept;

// Same options/result types as the ARM interpreter (stepnc::InterpretOptions/InterpretResult),
// so the pipeline treats both alike: stop_at_first_error, cancel, tool table, limits
// (max_nesting, arc_tolerance, max_errors).
[[nodiscard]] stepnc::InterpretResult interpret(const p21::Model& model,
                                                const stepnc::AttributeReader& attributes,
                                                canon::Sink& sink,
                                                const stepnc::InterpretOptions& options = {});

// The program's tree in the JSON shape of stepnc::inspect (docs/inspect.md): header, project →
// main workplan → executables, workpieces, tools (with their diameter, corner radius, length and
// number when the file gives them), statistics; and the diagnostics about the structure.
[[nodiscard]] stepnc::ProgramInfo inspect(const p21::Model& model, const express::SchemaSet& schema,
                                          const stepnc::InspectOptions& options = {});

}  // namespace ncpost::ap238
