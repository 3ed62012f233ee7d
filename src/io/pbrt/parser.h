// The pbrt-v4 parser: reads directives and calls one ParserTarget method per directive, so the same
// parser can drive the scene builder, a validator or a converter. Include/Import are expanded here.
#pragma once

#include <string>

#include "core/vec.h"
#include "io/pbrt/params.h"
#include "io/pbrt/tokenizer.h"

namespace phos::io::pbrt {

// One method per directive. `loc` is where the directive's keyword starts. Parameter lists are
// passed mutable-by-const: lookups mark parameters used (see ParamList).
class ParserTarget {
public:
    virtual ~ParserTarget() = default;

    // Transforms
    virtual void identity(const Loc& loc) = 0;
    virtual void translate(Vec3 d, const Loc& loc) = 0;
    virtual void scale(Vec3 s, const Loc& loc) = 0;
    virtual void rotate(float degrees, Vec3 axis, const Loc& loc) = 0;
    virtual void look_at(Vec3 eye, Vec3 target, Vec3 up, const Loc& loc) = 0;
    virtual void transform(const float m[16], const Loc& loc) = 0;         // column-major, as written
    virtual void concat_transform(const float m[16], const Loc& loc) = 0;  // column-major, as written
    virtual void coordinate_system(const std::string& name, const Loc& loc) = 0;
    virtual void coord_sys_transform(const std::string& name, const Loc& loc) = 0;
    virtual void reverse_orientation(const Loc& loc) = 0;

    // Rendering options (before WorldBegin)
    virtual void camera(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void film(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void pixel_filter(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void sampler(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void integrator(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void accelerator(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void color_space(const std::string& name, const Loc& loc) = 0;
    virtual void option(const Param& param, const Loc& loc) = 0;
    virtual void make_named_medium(const std::string& name, const ParamList& params, const Loc& loc) = 0;
    virtual void medium_interface(const std::string& inside, const std::string& outside, const Loc& loc) = 0;

    // World
    virtual void world_begin(const Loc& loc) = 0;
    virtual void attribute_begin(const Loc& loc) = 0;
    virtual void attribute_end(const Loc& loc) = 0;
    virtual void transform_begin(const Loc& loc) = 0;  // pbrt-v3 legacy
    virtual void transform_end(const Loc& loc) = 0;    // pbrt-v3 legacy
    // pbrt-v4's `Attribute "shape"|"light"|"material"|"medium"|"texture" params`: defaults for the
    // following directives of that kind in the attribute block. With applies_attributes() the
    // parser itself adds them to those directives' parameter lists (a parameter the directive gives
    // wins; defaults it does not read are not reported as unused); attribute() is called either way.
    virtual void attribute(const std::string& target, const ParamList& params, const Loc& loc) = 0;
    virtual bool applies_attributes() const { return true; }
    virtual void texture(const std::string& name, const std::string& type, const std::string& tex_class,
                         const ParamList& params, const Loc& loc) = 0;
    virtual void material(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void make_named_material(const std::string& name, const ParamList& params, const Loc& loc) = 0;
    virtual void named_material(const std::string& name, const Loc& loc) = 0;
    virtual void light_source(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void area_light_source(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void shape(const std::string& type, const ParamList& params, const Loc& loc) = 0;
    virtual void object_begin(const std::string& name, const Loc& loc) = 0;
    virtual void object_end(const Loc& loc) = 0;
    virtual void object_instance(const std::string& name, const Loc& loc) = 0;

    // Directives phos accepts but does nothing with (WorldEnd, TransformTimes, ActiveTransform...).
    virtual void ignored_directive(const std::string& name, const Loc& loc) = 0;
    // All input has been read.
    virtual void end_of_files(const Loc& loc) = 0;
};

// Parses `path` (and everything it includes) into `target`. Throws ParseError on malformed input.
// Include/Import paths are relative to the directory of the file that names them.
void parse_file(const std::string& path, ParserTarget& target);

}  // namespace phos::io::pbrt
