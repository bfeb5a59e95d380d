// §4 in 2D: the patch ψ_i(S_i) of a clicked face inside its domain triangle, laid flat in the
// triangle's own shape (its side lengths in D), the clicked face highlighted (spec/page.md PAGE-5).

const HIGHLIGHT = '#ff7f0e';

/** The faces of T′ (as drawn) of each patch, by counting sort over tp_patch. */
function facesByPatch(patch, patches) {
  const start = new Uint32Array(patches + 1);
  for (let f = 0; f < patch.length; f++) start[patch[f] + 1]++;
  for (let d = 0; d < patches; d++) start[d + 1] += start[d];
  const next = start.slice(0, patches);
  const faces = new Uint32Array(patch.length);
  for (let f = 0; f < patch.length; f++) faces[next[patch[f]]++] = f;
  return (d) => faces.subarray(start[d], start[d + 1]);
}

/** Domain face d laid flat: corners 0, 1 on the x axis, corner 2 above. */
function flatTriangle(data, d) {
  const p = data.array('d_positions'), t = data.array('d_faces');
  const x = [0, 1, 2].map((k) => [0, 1, 2].map((c) => p[3 * t[3 * d + k] + c]));
  const sub = (a, b) => a.map((v, i) => v - b[i]);
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const ab = sub(x[1], x[0]), ac = sub(x[2], x[0]);
  const len = Math.sqrt(dot(ab, ab));
  const along = dot(ac, ab) / len;
  return [[0, 0], [len, 0], [along, Math.sqrt(Math.max(dot(ac, ac) - along * along, 0))]];
}

export class PatchPanel {
  constructor(root, data) {
    this.data = data;
    this.root = root;
    this.title = root.querySelector('.panel-title');
    this.canvas = root.querySelector('canvas');
    this.faces = null;
  }

  hide() {
    this.root.hidden = true;
  }

  /** Shows the patch of face f of T′ as drawn; `original` is the face of T′ it stands for. */
  show(f, original) {
    const data = this.data;
    const patch = data.array('tp_patch');
    const d = patch[f];
    if (!this.faces) this.faces = facesByPatch(patch, data.report.domain.faces);
    this.root.hidden = false;
    this.root.dataset.patch = String(d);
    this.root.dataset.face = String(original);
    const sigma = data.array('tp_anisotropy')[f];
    this.title.textContent = `Patch ${d}: face ${original} of T′ in domain triangle ${d}` +
      ` (σ₁/σ₂ ${sigma > 0 ? sigma.toPrecision(3) : 'degenerate'})`;
    this.draw(d, f);
  }

  draw(d, clicked) {
    const ratio = window.devicePixelRatio || 1;
    const width = this.canvas.clientWidth, height = this.canvas.clientHeight;
    this.canvas.width = Math.round(width * ratio);
    this.canvas.height = Math.round(height * ratio);
    const g = this.canvas.getContext('2d');
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, width, height);
    const corners = flatTriangle(this.data, d);
    const xs = corners.map((c) => c[0]), ys = corners.map((c) => c[1]);
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const margin = 12;
    const scale = Math.min((width - 2 * margin) / (x1 - x0), (height - 2 * margin) / (y1 - y0));
    const ox = (width - scale * (x1 - x0)) / 2, oy = (height + scale * (y1 - y0)) / 2;
    const at = (b1, b2) => {
      const b0 = 1 - b1 - b2;
      const x = b0 * corners[0][0] + b1 * corners[1][0] + b2 * corners[2][0];
      const y = b0 * corners[0][1] + b1 * corners[1][1] + b2 * corners[2][1];
      return [ox + scale * (x - x0), oy - scale * (y - y0)];
    };
    const beta = this.data.array('tp_beta');
    const faces = this.faces(d);
    const path = (f) => {
      g.beginPath();
      for (let k = 0; k < 3; k++) {
        const [x, y] = at(beta[6 * f + 2 * k], beta[6 * f + 2 * k + 1]);
        if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
      }
      g.closePath();
    };
    g.fillStyle = '#f4f1e8';
    g.strokeStyle = faces.length > 3000 ? 'rgba(60,60,60,0.25)' : 'rgba(60,60,60,0.6)';
    g.lineWidth = 0.5;
    for (const f of faces) {
      path(f);
      g.fill();
      g.stroke();
    }
    path(clicked);
    g.fillStyle = HIGHLIGHT;
    g.fill();
    g.strokeStyle = '#000';
    g.lineWidth = 1;
    g.stroke();
    g.beginPath();
    corners.forEach((_, k) => {
      const b = [[0, 0], [1, 0], [0, 1]][k];
      const [x, y] = at(b[0], b[1]);
      if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
    });
    g.closePath();
    g.strokeStyle = '#222';
    g.lineWidth = 1.5;
    g.stroke();
  }
}

export { HIGHLIGHT };
