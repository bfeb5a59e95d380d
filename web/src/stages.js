// What the page says beside each stage: the paper's section in a few sentences, then this run's
// numbers from report.json (spec/page.md PAGE-4). Text only; page.js draws.

const fmt = (x, digits = 3) => (x === null || x === undefined ? '–' : Number(x).toPrecision(digits));
const int = (x) => Number(x).toLocaleString('en-US');

/** The paper's timing table (§6, the fandisk on a 400 MHz R12000, seconds). */
export const PAPER_TIMINGS = [
  ['mesh_reduction', 'mesh reduction', 35],
  ['geodesic_paths', 'geodesic paths', 16],
  ['parameterization', 'parameterization', 20],
  ['refinement', 'refinement', 1],
  ['decomposition', 'decomposition', 2],
  ['reconstruction', 'reconstruction', 1],
  ['total', 'total', 75],
];

export const STAGES = [
  {
    id: 's2',
    title: '§2 The domain',
    text(r) {
      const i = r.input, d = r.domain;
      const shape = `genus ${i.genus}` + (i.boundary_loops ? `, ${i.boundary_loops} boundary loop${i.boundary_loops > 1 ? 's' : ''}` : '') +
        (i.components > 1 ? `, ${i.components} components` : '');
      return [
        'The parameter domain D is a coarse triangulation of the same topology as T, made by ' +
          'half-edge collapses: each step moves one vertex onto a neighbour and removes the two triangles ' +
          'between them, choosing the collapse that changes the shape least and never one that would ' +
          'change the topology or fold a triangle. So every vertex of D is a vertex of T.',
        `Here T has ${int(i.vertices)} vertices and ${int(i.faces)} faces (${shape}); D has ` +
          `${int(d.vertices)} vertices, ${int(d.edges)} edges and ${int(d.faces)} faces` +
          (d.faces_asked ? ` (${int(d.faces_asked)} asked).` : ' (given by the user).') +
          ' D is drawn over T with straight edges between its vertices.',
      ];
    },
  },
  {
    id: 's3',
    title: '§3 The network of curves',
    text(r) {
      const p = r.partition;
      return [
        'Each edge of D becomes a curve on T between its two end vertices: the exact shortest geodesic, ' +
          'found by window propagation inside an ellipse around the edge that is widened until the path ' +
          'provably lies inside it. The curves are embedded into T by inserting their points, which gives ' +
          'the refined triangulation T′. Two conditions make the curves cut T into one patch per triangle ' +
          'of D: (1) curves meet only at common end vertices, and (2) around each vertex they leave in the ' +
          'order of D\'s edges. Where geodesics would cross, a curve is restricted to the region the others leave free.',
        `Here ${int(p.paths)} curves of total length ${fmt(p.total_length, 4)}: ${int(p.geodesic_edges)} exact ` +
          `geodesics, ${int(p.restricted_edges)} restricted curves and ${int(p.boundary_edges)} boundary arcs. ` +
          `T′ has ${int(p.refined_vertices)} vertices and ${int(p.refined_faces)} faces; each patch has its colour.`,
      ];
    },
  },
  {
    id: 's4',
    title: '§4 The parameterization',
    text(r) {
      const m = r.parameterization, d = m.distortion, a = d.anisotropy;
      return [
        'Each patch is mapped onto its triangle of D: its three boundary curves by chord length onto the ' +
          'triangle\'s sides, and every interior vertex to a convex combination of its neighbours\' images ' +
          '(Floater\'s shape-preserving weights), one sparse linear system per patch. Tutte\'s theorem, as ' +
          'extended by Floater, makes each map one-to-one (Proposition 1); together they give φ from D onto T. ' +
          'The checkerboard of D carried onto T by φ shows the map.',
        `Here ${int(m.patches)} patches, ${m.weights} weights, solver ${m.solver}; ` +
          `${m.certified ? 'every patch certified one-to-one' : 'NOT certified'}. Distortion (σ₁ ≥ σ₂, the ` +
          `singular values of each face's map, normalised): L2 stretch ${fmt(d.l2_stretch, 4)}; σ₁/σ₂ median ` +
          `${fmt(a.p50)}, 99th percentile ${fmt(a.p99)}, maximum ${fmt(a.max)}. Click a face to see its patch ` +
          'in its domain triangle.',
      ];
    },
  },
  {
    id: 's5',
    title: '§5 Remeshing and wavelets',
    text(r) {
      if (!r.wavelet) return ['This run has no §5 stage (fhr run --levels J).'];
      const w = r.wavelet, m = r.remesh;
      return [
        'Sampling φ at the vertices of D^j, D split j times into four, gives surfaces f^j with ' +
          'subdivision connectivity. Prewavelets decompose f^J into f^0 and wavelet coefficients for each ' +
          'level; reconstructing from only the largest coefficients compresses the surface (§6).',
        `Here J = ${m.level}: f^J has ${int(m.vertices)} vertices and ${int(m.faces)} faces, ` +
          `Hausdorff distance ${fmt(m.hausdorff)} to T (${fmt(100 * m.hausdorff_relative_to_bbox_diagonal, 2)} % of ` +
          `its diagonal); ${int(w.coefficients)} coefficients.`,
      ];
    },
  },
  {
    id: 'run',
    title: 'Timings and verdict',
    text(r) {
      const o = r.parameterization.oracle;
      return [
        'The stages\' wall-clock seconds beside the paper\'s timing table (the fandisk on a 400 MHz ' +
          'R12000 in 2001), and the verdict of fhr\'s independent oracle (fhr verify) on param.fhrp, check by check.',
        `Verdict: ${o.valid ? 'valid' : 'INVALID'} (${o.checks.filter((c) => c.status === 'pass').length} of ` +
          `${o.checks.length} checks pass).`,
      ];
    },
  },
];
