#pragma once
// A course profile's formula fields (docs/course-profile.md): a checkpoint's `formula` and a
// mistake's `reading`, each checked field by field into the reader's first problem (JsonReader).
#include "core/json_reader.h"
#include "course/course.h"

namespace shadelab::course {

// What the checkpoint's formula reads a mistake as: its variant (the formula's own by default)
// and the values it changes, by their names in a report: three numbers for a colour or the
// light's position, one for the exponent.
grade::FormulaReading formula_reading(const JsonReader& r);

// A checkpoint's formula: its terms, and varyings its reference's vertex shader writes; the
// uniforms it reads by role, from `course`'s uniforms (read before the checkpoints).
CheckpointFormula checkpoint_formula(const JsonReader& f, const Preset* reference, const Course& course);

}  // namespace shadelab::course
