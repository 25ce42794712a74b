#pragma once
// The conformal geometry in one include: entities (Table 1), meets
// (§1.6), reflections (§1.7), inside/outside (§2.4.1) and the local-origin
// precision remedy. Twin: traditional/geometry.hpp.
#include "cga/geometry/entities.hpp"
#include "cga/geometry/inside.hpp"
#include "cga/geometry/local_origin.hpp"
#include "cga/geometry/meet.hpp"
#include "cga/geometry/reflect.hpp"
