//! # fixshade
//!
//! Flat (Lambert), Gouraud and Phong shading of 3D triangle meshes on small
//! displays, with integer and fixed-point arithmetic only.
//!
//! The crate is `no_std`, allocates nothing and contains no `unsafe` code.
//! Every buffer (frame, depth, prepared frame) belongs to the caller.
//!
//! The pipeline, one module per stage:
//!
//! - [`num`]: number formats, numeric profiles (fixed `fast` and `precise`,
//!   the `f32` and `f64` float twins), conversions that saturate,
//!   approximations with stated error bounds;
//! - [`geom`]: vectors, matrices, transforms;
//! - [`mesh`]: meshes as constant Q1.14 data, vertex normals, built-in shapes;
//! - [`scene`]: camera, objects, lights;
//! - [`illum`]: the Phong illumination model at one point;
//! - [`render`]: preparing a frame (transform, light, cull, clip, project)
//!   and rasterizing it band by band;
//! - [`raster`]: screen-space triangles: setup, exact integer DDA edge
//!   walking with the top-left rule, spans with depth test and shading;
//! - [`target`]: pixel formats, frame and depth buffers, bands of rows.
//!
//! # Layers
//!
//! Dependencies run one way. Each module imports only the modules listed
//! before it on its line (a test, `tests/layers.rs`, reads every `crate::`
//! and `super::` path of `src/` and fails on any other import):
//!
//! | module | may import |
//! |---|---|
//! | [`num`] | nothing |
//! | `pixel` (private: [`target::Rgb8`], [`target::MAX_SCREEN`]) | nothing |
//! | [`geom`] | `num` |
//! | [`mesh`] | `num`, `geom` |
//! | [`illum`] | `num`, `geom`, `mesh` |
//! | [`scene`] | `num`, `pixel`, `geom`, `mesh`, `illum` |
//! | [`target`] | `num`, `pixel` |
//! | [`raster`] | `num`, `pixel`, `target` |
//! | [`render`] | every module above |
//!
//! Two chains rise from `num`: the 3D one (geom → mesh → illum → scene)
//! and the screen one (target → raster), which knows nothing of meshes,
//! scenes or light. [`render`] is the one module that joins them: it
//! prepares a scene into screen-space triangles, then rasterizes them into
//! targets. So in the pipeline order num → geom → mesh → scene → render →
//! raster → target, the first five each use only those before them, while
//! render uses raster and raster uses target (data flows down the screen
//! chain, imports point up it). Exact integer geometry of Q1.14 positions
//! (face normals, culling planes and cones, bounding spheres) lives in
//! `geom`; `mesh` re-exports what its tables' users need (for example
//! [`mesh::face_normal`], [`mesh::Bound`]).
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs, missing_debug_implementations)]

// The `armv6m` alias comes from build.rs: a build without it (a copy of the
// sources that left the build script out) would take the ARMv7-M paths on a
// Cortex-M0 and call the compiler's 64-bit helpers.
#[cfg(all(target_arch = "arm", not(target_has_atomic = "32"), not(armv6m)))]
compile_error!("the `armv6m` cfg alias is missing: build.rs did not run");

pub mod geom;
pub mod illum;
pub mod mesh;
pub mod num;
mod pixel;
pub mod raster;
pub mod render;
pub mod scene;
pub mod target;

#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
