// The run's data as src/fhr/app/page.cpp embeds it (spec/page.md PAGE-3): one JSON document in
// <script id="fhr-data">, each array base64 of little-endian typed data. Arrays are decoded when
// first asked for, so that the first frame waits only for what it draws.

function bytesOf(base64) {
  const text = atob(base64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  return bytes;
}

function decode(entry) {
  const bytes = bytesOf(entry.data);
  const n = entry.count;
  switch (entry.type) {
    case 'u8':
      return bytes;
    case 'u32':
      return new Uint32Array(bytes.buffer, 0, n);
    case 'f32':
      return new Float32Array(bytes.buffer, 0, n);
    case 'u16n': { // values in [0, 1]: q / 65535
      const q = new Uint16Array(bytes.buffer, 0, n);
      const out = new Float32Array(n);
      for (let i = 0; i < n; i++) out[i] = q[i] / 65535;
      return out;
    }
    case 'q16': { // points: min + q·(max − min)/65535 per coordinate
      const q = new Uint16Array(bytes.buffer, 0, n);
      const out = new Float32Array(n);
      const scale = [0, 1, 2].map((c) => (entry.max[c] - entry.min[c]) / 65535);
      for (let i = 0; i < n; i++) out[i] = entry.min[i % 3] + q[i] * scale[i % 3];
      return out;
    }
    default:
      throw new Error(`fhr page: unknown array type ${entry.type}`);
  }
}

/** The page's data: its JSON fields, and `array(name)` (null when the run has no such array). */
export function loadData() {
  const data = JSON.parse(document.getElementById('fhr-data').textContent);
  const decoded = new Map();
  data.has = (name) => name in data.arrays;
  data.array = (name) => {
    if (!data.has(name)) return null;
    if (!decoded.has(name)) decoded.set(name, decode(data.arrays[name]));
    return decoded.get(name);
  };
  return data;
}
