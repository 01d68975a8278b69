/* Host/device shared parameter layouts of every kernel.
 *
 * This is the one file that both the host (C++) and the device (OpenCL C, and
 * the per-ISA CPU translation units) read, so the layouts cannot drift apart.
 * Members are only int and float (4 bytes each, no padding), so the host's
 * struct and the OpenCL kernel argument have the same bytes.
 */
#ifndef PENUMBRA_KERNEL_PARAMS_H
#define PENUMBRA_KERNEL_PARAMS_H

#ifdef __cplusplus
namespace penumbra {
#endif

/* An image's geometry in elements: planes of `height` rows of `pitch`
 * elements, of which the first `width` are pixels. */
typedef struct {
    int width;
    int height;
    int pitch;
    int plane_pitch;
} pn_dims;

/* How the shadow map's texels and the receivers' z are stored, and their
 * conversion to the normalised linear depth the methods use
 * (kernels/depth_convention.h; the host fills it from penumbra::DepthConvention,
 * host/src/depth_convention.cpp). */
#define PN_DEPTH_NORMALIZED 0  /* [0, 1], used as stored */
#define PN_DEPTH_LINEAR 1      /* distance in [near, far] */
#define PN_DEPTH_PERSPECTIVE 2 /* D3D / Vulkan [0, 1] projected depth */
#define PN_DEPTH_REVERSED 3    /* reversed Z: 1 - the perspective depth */
typedef struct {
    int kind;    /* PN_DEPTH_* */
    float low;   /* the stored range: [0, 1], or [near, far] (linear) */
    float high;
    float scale; /* linear: 1 / (far - near); perspective, reversed: k = (far - near) / near; else 0 */
} DepthConversion;

/* The shadow map as the direct window sums (kernels/box_window.h) and the
 * soft percentage-closer discs (kernels/hammersley.h) read it: `rows` holds
 * the map's rows [first_row, first_row + rows.height), stored in
 * `convention`. The host passes the whole map (first_row 0, the map's
 * convention); the CPU schedule may pass a band of rows it converted to
 * normalised depth once (simd/cpu_direct_sums.cpp). Zeroed (the table
 * lookups sharing the Params, Params filled by hand): the whole map in the
 * receivers' convention (direct_map, kernels/depth_convention.h). */
typedef struct {
    pn_dims rows;
    int first_row;
    DepthConversion convention;
} DirectMap;
/* Written into every lane of a strip by an entry reading a band whose taps
 * would reach rows the band does not hold (a soft disc wider than the CPU
 * schedule guessed): the schedule runs that strip again over the whole
 * stored map (simd/cpu_direct_sums.h). Never a result: those lie in [0, 1]. */
#define PN_BAND_RERUN (-1.0f)

/* Summed-area table of depth moments (kernels/moment_table.h).
 * The table stores inclusive sums S(x, y) = sum of m(i, j) for i <= x, j <= y;
 * row y lives at table + (y + 1) * pitch, so that row -1 (table + 0) is a zero
 * row and column -1 is the last padding element of the row before, also zero.
 * `table.width` and `table.height` are the map's size (not W + 1). */
typedef struct {
    pn_dims depth;     /* the depth map: one plane, values in [0, 1] */
    pn_dims table;     /* `moments` planes of inclusive sums */
    pn_dims columns;   /* column accumulators: `moments` planes, one row per band */
    int moments;       /* values per texel: 2 (z, z^2; w+, w+^2) or 4 (z .. z^4; both warps) */
    int limbs;         /* exact tables: 16-bit limbs per value (2 or 3); float tables: 1.
                          The table has moments x limbs planes (kernels/moment_table.h) */
    int encoding;      /* PN_TABLE_POWERS or PN_TABLE_EVSM */
    int band_height;   /* rows per band in the banded (OpenCL) schedule */
    float exponent_positive; /* PN_TABLE_EVSM: c+ */
    float exponent_negative; /* PN_TABLE_EVSM: c- */
    DepthConversion convention; /* the depth map's */
} SatParams;
#define PN_TABLE_POWERS 0 /* values z^k */
#define PN_TABLE_EVSM 1   /* values: EVSM's warps and their squares (kernels/exponential_warp.h) */

/* Chebyshev lookups (kernels/chebyshev.h, vsm.h, vssm.h). */
typedef struct {
    pn_dims table;          /* the moment table (see SatParams) */
    pn_dims receivers;      /* planes u, v, z */
    pn_dims out;            /* one plane: visibility */
    int radius;             /* vsm: box radius in texels */
    int max_radius;         /* vssm: largest filter radius the table allows (texels) */
    float min_variance;     /* variance floor, in depth^2 */
    float bleed;            /* light-bleeding reduction in [0, 1) */
    float light_size;       /* vssm: texture units, the search width and L in w = L (z - z_b) / z_b */
    int limbs;              /* exact tables: 16-bit limbs per value (SatParams) */
    DepthConversion convention; /* the receivers' z (and the map's: its table, or `direct`) */
    DirectMap direct;       /* vsm_direct: the map's rows it reads */
} ChebyshevParams;

/* Cross-bilateral filter of a mask guided by depth (kernels/bilateral.h). The
 * window's taps (offsets and spatial weights) are buffers the host computes
 * once per call. */
typedef struct {
    pn_dims mask;          /* 1 to 4 planes: the values filtered */
    pn_dims guide;         /* one plane: depth */
    pn_dims normals;       /* 3 planes (x, y, z) when use_normals, else unused */
    pn_dims out;           /* as many planes as the mask */
    pn_dims pass;          /* separable: the horizontal pass's rows, planes as the mask */
    int channels;          /* 1 to 4 */
    int radius;            /* every tap offset lies in [-radius, radius] */
    int taps;              /* taps in the window (per pass, separable) */
    int threshold;         /* 1: hard rejection; 0: Gaussian range weight */
    int relative;          /* 1: depth differences divided by |centre depth| */
    int use_normals;       /* 1: normals weigh too */
    int pass_first_row;    /* separable: the image row held by row 0 of `pass` */
    float depth_scale;     /* Gaussian: sqrt(log2(e) / 2) / sigma_d, so w = 2^-(d depth_scale)^2 */
    float depth_threshold; /* threshold: the largest accepted |difference| */
    float normal_scale;    /* log2(e) / (2 sigma_n^2) */
} BilateralParams;

/* Sphere-traced SDF soft shadows (kernels/sdf.h). Analytic primitives are one
 * float buffer of records grouped by kind, in this order, each kind's count
 * below (world units; host: host/src/sdf_analytic_scene.cpp packs them):
 *   plane   4 floats: unit normal n (3), offset: the solid dot(p, n) <= offset
 *   sphere  4 floats: centre (3), radius
 *   box    16 floats: centre (3), half size (3), the box's local x, y, z axes
 *                     in world space (3 x 3, unit), 1 unused
 *   capsule 8 floats: a (3), b - a (3), 1 / |b - a|^2 (0 when a = b), radius */
#define PN_SDF_PLANE_FLOATS 4
#define PN_SDF_SPHERE_FLOATS 4
#define PN_SDF_BOX_FLOATS 16
#define PN_SDF_CAPSULE_FLOATS 8
#define PN_SDF_CLASSIC 0  /* estimate: k h / t */
#define PN_SDF_IMPROVED 1 /* estimate: k d / (t - y), two-step closest approach */
#define PN_SDF_INNER 2    /* estimate: signed k h / t through solids, smoothstep from [-1, 1] */
typedef struct {
    pn_dims receivers;       /* 3 planes: world x, y, z */
    pn_dims normals;         /* 3 planes: unit normals (read when normal_offset != 0) */
    pn_dims out;             /* plane 0 visibility; plane 1 steps when write_steps */
    int grid_nx, grid_ny, grid_nz;  /* grid: nodes per axis (>= 2), x fastest */
    int planes, spheres, boxes, capsules;  /* analytic: records of each kind */
    int max_steps;           /* distance evaluations per ray (>= 1) */
    int estimate;            /* PN_SDF_CLASSIC, PN_SDF_IMPROVED or PN_SDF_INNER */
    int light_is_direction;  /* 1: light_* is the unit direction to the light */
    int write_steps;         /* 1: out plane 1 gets each ray's distance evaluations */
    float light_x, light_y, light_z;  /* the light's centre, or the direction */
    float k;                 /* hardness (> 0): 1 / k is the safe angle counted as lit */
    float k_per_distance;    /* > 0, a light at a point: k = this x the receiver's distance to it */
    float t_min, t_max;      /* march interval along the ray (world units) */
    float hit_epsilon;       /* a distance below this is a hit (> 0) */
    float normal_offset;     /* receivers lifted along their normals (world units) */
    float grid_x, grid_y, grid_z;  /* grid: world position of node (0, 0, 0) */
    float voxel, inv_voxel;  /* grid: node spacing and its reciprocal */
} SdfParams;

/* The moment family: MSM, moment soft shadows, EVSM (kernels/moment_quantize.h,
 * exponential_warp.h, encoded_table.h, evsm.h, msm.h, msm_soft.h). */
#define PN_ENCODE_MSM 0           /* 4 channels: the optimized 16-bit moment encoding */
#define PN_ENCODE_EVSM 1          /* 2 or 4 channels: the exponential warps */
#define PN_MOMENTS_POWER 0        /* an MSM table of sums of z, z^2, z^3, z^4 (limb or float) */
#define PN_MOMENTS_OPTIMIZED16 1  /* an MSM table of sums of optimized 16-bit moments */
typedef struct {
    pn_dims depth;           /* one plane: depths in [0, 1] */
    pn_dims table;           /* `channels` planes of inclusive sums (SatParams' layout) */
    pn_dims columns;         /* `channels` planes, one row per band: its column totals */
    int channels;            /* 4 (MSM), 2 or 4 (EVSM) */
    int band_height;         /* rows per band */
    int encoding;            /* PN_ENCODE_MSM or PN_ENCODE_EVSM */
    int quantize;            /* float tables: 1 rounds each value to a 16-bit step */
    float exponent_positive; /* EVSM: c+ */
    float exponent_negative; /* EVSM: c- */
    DepthConversion convention; /* the depth map's */
} EncodedSatParams;

typedef struct {
    pn_dims table;           /* the table (SatParams' layout) */
    pn_dims receivers;       /* planes u, v, z */
    pn_dims out;             /* one plane: visibility */
    int radius;              /* msm, evsm: box radius in texels */
    int max_radius;          /* msm_soft: the largest filter radius the table allows */
    int storage;             /* msm: PN_MOMENTS_POWER (z..z^4) or PN_MOMENTS_OPTIMIZED16 */
    int channels;            /* evsm: 2 (positive warp) or 4 (both) */
    int limbs;               /* exact limb tables (msm power moments, evsm): limbs per value */
    float moment_bias;       /* msm: alpha in [0, 1) */
    float pivot_floor;       /* msm: a Hankel pivot (depth^2 units) at or below this is zero (kernels/msm.h) */
    float depth_bias;        /* subtracted from the receiver's depth */
    float light_size;        /* msm_soft: as ChebyshevParams' */
    float plane_bias;        /* msm_soft: share of the receiver plane's drop over each window (0 = off) */
    float plane_bias_max;    /* msm_soft: its largest value, depth units */
    float min_variance;      /* evsm: depth^2, scaled by the warp's squared slope */
    float bleed;             /* evsm: light-bleeding reduction in [0, 1) */
    float exponent_positive; /* evsm: c+ */
    float exponent_negative; /* evsm: c- */
    DepthConversion convention; /* the receivers' z (and the map's: its table, or `direct`) */
    DirectMap direct;        /* msm_direct, evsm_direct: the map's rows they read */
} MomentParams;

/* The percentage-closer family (kernels/depth_bias.h, pcf.h, pcf_gauss.h,
 * pcf_disc.h): lookups that read the shadow map itself, one float plane of
 * depths in [0, 1], and compare each tap with the receiver. */
#define PN_BIAS_CONSTANT 0       /* every tap: depth >= z - constant */
#define PN_BIAS_SLOPE 1          /* constant + slope_scale x the receiver's depth step per texel, clamped */
#define PN_BIAS_RECEIVER_PLANE 2 /* the tap's depth on the receiver's plane (Isidoro 2006), clamped */
typedef struct {
    int mode;          /* PN_BIAS_* */
    float depth_bias;  /* depth units: the constant mode's bias, the others' base ("constant" is an OpenCL keyword) */
    float slope_scale; /* slope: bias per unit of the receiver's depth change across one texel */
    float low;         /* slope, receiver-plane: the bias is clamped to [low, high] (Toy Story 3; --bias-min) */
    float high;        /* --bias-max */
} PcfBias;

/* Receivers of the family: planes u, v, z and, for the slope and
 * receiver-plane modes, dz/du, dz/dv (depth per unit of texture coordinate)
 * and a plane flag (1: the derivatives hold; 0: they cross a depth
 * discontinuity, use the constant bias); host/src/receiver_plane.cpp. */
#define PN_PCF_PLANE_DZDU 3
#define PN_PCF_PLANE_DZDV 4
#define PN_PCF_PLANE_OK 5
#define PN_PCF_PLANES_WITH_DERIVATIVES 6

#define PN_PCF_MAX_GRID 16  /* pcf_gauss: grid side limit (a (n+1)^2 texel footprint) */
#define PN_PCF_MAX_TAPS 256 /* pcf_disc: tap count limit */
typedef struct {
    pn_dims depth;     /* the shadow map: one plane */
    pn_dims receivers; /* 3 planes (u, v, z), or 6 with the derivatives (above) */
    pn_dims out;       /* one plane: visibility */
    PcfBias bias;
    int radius;        /* pcf: box radius in texels (>= 0) */
    int grid;          /* pcf_gauss: taps per side (4: Toy Story 3) */
    int taps;          /* pcf_disc: taps of the disc (1 .. PN_PCF_MAX_TAPS) */
    int rotate;        /* pcf_disc: 1 rotates the pattern per receiver from a 4x4 tile */
    float sigma;       /* pcf_gauss: the Gaussian's standard deviation, in tap spacings (texels) */
    float disc_radius; /* pcf_disc: the disc's radius in texels (> 0) */
    DepthConversion convention; /* the map's and the receivers' z */
} PcfParams;

/* The soft members of the family (kernels/pcss.h, kernels/burley.h), on the
 * Hammersley disc (kernels/hammersley.h). Radii and light_size in texture units. */
#define PN_SOFT_MAX_SAMPLES 1024 /* taps per pass (penumbra/soft_pcf.h, kMaxSoftSamples) */
typedef struct {
    pn_dims depth;       /* the shadow map: one plane */
    pn_dims receivers;   /* as PcfParams */
    pn_dims out;         /* one plane: visibility */
    PcfBias bias;        /* the family's bias; burley: bias.depth_bias is the cone's base bias */
    int blocker_samples; /* taps of the blocker search (1 .. PN_SOFT_MAX_SAMPLES) */
    int filter_samples;  /* taps of the filter */
    float light_size;    /* pcss: search diameter, and L in w = L (z - z_b) / z_b */
    float min_radius;    /* burley: filter radius at contact */
    float max_radius;    /* burley: depth-pass radius R and the widest filter */
    float bias_slope;    /* burley: the cone's slope at z = 0, depth per texture unit */
    float bias_slope_per_depth; /* burley: the slope's growth per unit of receiver depth z */
    float falloff;       /* burley: opacity falloff distance in depth units; 0 = off */
    DepthConversion convention; /* the map's and the receivers' z */
    DirectMap direct;    /* the map's rows the taps read (see DirectMap) */
} SoftPcfParams;

/* Ambient light rigs in spherical harmonics and ambient volumes
 * (kernels/ambient_sh.h, kernels/ambient_volumes.h; host/src/ambient.cpp).
 * The rigs' weights are per channel (R, G, B) the PN_SH_TERMS weights of the
 * polynomial basis of kernels/ambient_sh.h, channel-major. */
#define PN_SH_TERMS 9               /* order 2: 9 coefficients per channel */
#define PN_AMBIENT_VOLUME_FLOATS 16 /* one volume record (kernels/ambient_volumes.h) */
#define PN_AMBIENT_SPHERE 0
#define PN_AMBIENT_BOX 1
#define PN_AMBIENT_LIGHT_ONLY 0     /* the light rig alone */
#define PN_AMBIENT_BLEND_PLANE 1    /* blend factor from receiver plane factor_plane */
#define PN_AMBIENT_BLEND_VOLUMES 2  /* blend factor from the volumes at the receiver's position */
typedef struct {
    pn_dims receivers;   /* planes: normal x, y, z, then the factor or the position */
    pn_dims out;         /* ambient_sh: 3 planes R, G, B; ambient_volumes: 1 plane, the factor */
    int blend;           /* PN_AMBIENT_* */
    int light_terms;     /* 4 (order 1) or 9 (order 2) */
    int dark_terms;      /* 4 (order 1, or the notes' cheaper dark) or 9 */
    int factor_plane;    /* PN_AMBIENT_BLEND_PLANE: the factor's receiver plane */
    int position_plane;  /* volumes: the receiver plane of world x (then y, z) */
    int volume_count;    /* records in the source */
    float light[3 * PN_SH_TERMS];
    float dark[3 * PN_SH_TERMS];
} AmbientParams;

/* Deep shadow map lookups (kernels/dsm_lookup.h): the map is three arrays
 * (penumbra/deep_shadow_map.h): offsets (uint, width*height + 1), depths and
 * transmittances (float, one per vertex). */
#define PN_DSM_BOX 0    /* (2r+1)^2 pixels around the receiver's, equal weights */
#define PN_DSM_TENT 1   /* (2r+2)^2 pixels, bilinear weights of half-width r + 1 */
#define PN_DSM_BINARY 0 /* each pixel's vertices searched by bisection */
#define PN_DSM_LINEAR 1 /* ... front to back */
typedef struct {
    pn_dims map;       /* the deep map's pixels (width, height; the arrays are packed) */
    pn_dims receivers; /* planes u, v, z */
    pn_dims out;       /* one plane: visibility */
    int filter;        /* PN_DSM_BOX or PN_DSM_TENT */
    int radius;        /* texels, >= 0 */
    int search;        /* PN_DSM_BINARY or PN_DSM_LINEAR */
    int search_top;    /* binary: the largest power of two <= the most vertices of one pixel (0 if none) */
    int vertices;      /* vertices of the map (< 2^30) */
    int last_vertex;   /* max(vertices - 1, 0): the arrays hold at least one element each */
    float bias;        /* subtracted from the receiver's depth */
} DsmParams;

/* The cascaded shadow mask (kernels/cascades.h; penumbra/cascades.h). Per
 * cascade c (finest first) a world point p lands at
 *     u = dot(p, axis_u) u_scale[c] + u_offset[c]   (v, z alike)
 * in [0, 1]^3 inside its orthographic box; biases are in that cascade's depth
 * units. Keep PN_CASCADES_MAX equal to penumbra::kMaxCascades. */
#define PN_CASCADES_MAX 4
#define PN_CASCADE_SELECT_BOX 0   /* the finest bounding box holding the PCF footprint (Zhang 2009) */
#define PN_CASCADE_SELECT_SPLIT 1 /* the first split whose far view depth lies beyond the pixel */
#define PN_CASCADE_PLANES 5       /* receivers: world x, y, z, view depth, surface flag */
typedef struct {
    pn_dims maps;      /* one plane: the cascades' maps stacked, cascade c in rows [c map_height, (c+1) map_height) */
    pn_dims receivers; /* PN_CASCADE_PLANES planes */
    pn_dims out;       /* 2 planes: visibility, the cascade used (-1 for none) */
    int cascades;      /* 1 .. PN_CASCADES_MAX */
    int map_height;    /* rows of one cascade's map */
    int select;        /* PN_CASCADE_SELECT_* */
    int grid;          /* Gaussian PCF taps per side (4: Toy Story 3) */
    float sigma;       /* its standard deviation, texels */
    float axis_u[3], axis_v[3], axis_z[3]; /* the light's frame (unit vectors, world) */
    float u_scale[PN_CASCADES_MAX], u_offset[PN_CASCADES_MAX];
    float v_scale[PN_CASCADES_MAX], v_offset[PN_CASCADES_MAX];
    float z_scale[PN_CASCADES_MAX], z_offset[PN_CASCADES_MAX];
    float margin[PN_CASCADES_MAX];      /* box selection: texture units kept clear of the edge */
    float split_far[PN_CASCADES_MAX];   /* split selection: the split's far view depth */
    float static_bias[PN_CASCADES_MAX]; /* where the derivatives do not hold */
    float bias_min[PN_CASCADES_MAX];
    float bias_max[PN_CASCADES_MAX];
} CascadeParams;

/* Volumetric-obscurance SSAO with paired samples (kernels/ssao_vo.h;
 * host/src/ssao.cpp). The pattern and the rotation tile are the source. */
#define PN_SSAO_PAIRED 0      /* an unusable sample: its partner's inverse, else 1/2 */
#define PN_SSAO_ZERO 1        /* an unusable sample: 0 */
#define PN_SSAO_HALF 2        /* an unusable sample: 1/2 */
#define PN_SSAO_RENORMALISE 3 /* unusable samples dropped, the weights renormalised */
typedef struct {
    pn_dims depth;       /* one plane: view depth, world units, 0 = no surface */
    pn_dims out;         /* one plane: obscurance or accessibility */
    int pairs;           /* sample pairs in the pattern */
    int unusable;        /* PN_SSAO_* */
    int rotate;          /* 1: the 4x4 rotation tile turns the pattern per pixel */
    int accessibility;   /* 1: out = 1 - saturate(2 o - 1); 0: out = o */
    float radius;        /* R: the sphere's radius, world units */
    float focal;         /* focal length in pixels: (height / 2) / tan(vertical fov / 2) */
    float max_pixels;    /* the screen radius's cap, pixels */
    float falloff;       /* > 1: occluders nearer than the centre by falloff R' or more count not */
    float centre_weight; /* the centre line's share of the sphere's volume */
} SsaoParams;
/* Pismo's shadow-ray test (kernels/pismo.h): the maps are packed arrays
 * (host/src/pismo_pack.cpp; the record layouts below are the two files'
 * contract). Every map has the same size. */
#define PN_PISMO_CAMERA_FLOATS 16  /* position, right, down, forward, 2 tan(fov/2), 2 tan(fov/2) / W, unused x2 */
#define PN_PISMO_TRIANGLE_UINTS 5  /* corners a, b, c (map indices), first ray, end of its rays */
#define PN_PISMO_RAY_FLOATS 4      /* barycentric w_a, w_b, w_c, weight */
typedef struct {
    pn_dims receivers;  /* planes x, y, z: world position, then with `normals` the normal's x, y, z, then with
                           `surface_ids` the receiver's surface id (a chunk of the caller's rows) */
    pn_dims out;        /* estimates: maps x receiver rows; visibility: one plane of the receivers' size */
    pn_dims estimates;  /* visibility: the estimates image (maps x receiver rows); unused by the estimates */
    int map_width, map_height;
    int maps;           /* < 2^31 / (map_width map_height): pixel indices are int */
    int triangles;
    int last_depth;     /* max(depths - 1, 0): the depth array holds at least one element */
    float bias_texels;  /* texel footprints at the point's depth */
    int normals;        /* 1: the receivers carry normals, and their own surface takes part (kernels/pismo.h) */
    float max_slope;    /* with normals: the slope term's cap, texels */
    int surface_ids;    /* 1: the receivers carry a 7th plane, their surface id, and the test maps an id per layer */
    float other_bias_texels; /* with surface_ids: the bias of a layer of another surface than the receiver's */
} PismoParams;

#ifdef __cplusplus
}  /* namespace penumbra */
#endif

#endif
