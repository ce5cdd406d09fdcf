/*
 * Rolling: the body's surface passes through the cells along the body's
 * axis 1 (x, along length) while the cells stay where they are.  Over a step
 * the material moves by `shift` cells toward -x (shift > 0: it enters at the
 * leading edge x = +length/2 and leaves at -length/2; shift < 0 the other
 * way), carrying its elastic state: the cell at column i takes the state of
 * the material that was at column i + shift, its elastic force (in yield
 * coordinates), normal force and elastic displacement u - s; it keeps its
 * own committed displacement u, so that the next step's increment is the
 * body's creep at that cell, and its own dissipated energy (the energy the
 * cells count stays counted when the material leaves).
 *
 * The material enters unloaded at the leading edge, at the pose of the
 * moment it crosses it: the boundary value u - s = 0 on the edge is held by
 * ghost columns beyond it, each the mirror image of a column inside with
 * its force and elastic displacement negated (second order, as a
 * cell-centred scheme holds a boundary value): in steady stick, where u - s
 * grows linearly from the edge, what a cell takes from beyond the edge plus
 * the step's creep is exactly the cell's mean, whatever the shift.  Beyond
 * the mirror's reach (a shift of more than the whole grid) it is unloaded.
 *
 * A whole shift moves the states exactly; a fractional one takes the states
 * of the two columns it falls between, weighted linearly (first-order
 * upwind: its numerical diffusion falls with the cell size).  A weighted
 * state stays inside the yield surface, |a| <= N being convex in (a, N).
 * No FMI in it.
 */
#ifndef CELLS_TRANSPORT_H
#define CELLS_TRANSPORT_H

#include "cells/cells.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The committed states of `src` (cells_committed: an array or a step's
 * results) moved by `shift` columns into out[c], c = i + n1 j; out must
 * not be a buffer src reads. */
void cells_transport(const cells_setup *g, double shift, const cells_source *src, oc_state out[]);

#ifdef __cplusplus
}
#endif
#endif
