// The page's look: a side bar with the stages, their text, controls and legends; the 3D view
// filling the rest; the 2D patch panel over its lower right corner. Fonts: DejaVu (Debian's
// fonts-dejavu-core, which ./run installs), so that screenshots compare across machines.

export const CSS = `
* { box-sizing: border-box; }
html, body { margin: 0; height: 100%; font: 14px/1.45 "DejaVu Sans", sans-serif; color: #1d1d1d; background: #fafaf7; }
#app { display: grid; grid-template-columns: 380px 1fr; height: 100%; }
#side { overflow-y: auto; padding: 12px 16px; border-right: 1px solid #ddd; background: #fff; }
#side h1 { font-size: 17px; margin: 0 0 2px; }
#side .sub { color: #666; font-size: 12px; margin-bottom: 10px; }
#stages { display: flex; flex-wrap: wrap; gap: 4px; margin-bottom: 10px; }
#stages button { font: inherit; font-size: 13px; padding: 4px 8px; border: 1px solid #bbb; border-radius: 4px; background: #f3f3f0; cursor: pointer; }
#stages button[aria-pressed="true"] { background: #264f78; border-color: #264f78; color: #fff; }
#text p { margin: 0 0 8px; }
.controls { margin: 10px 0; display: grid; gap: 6px; }
.controls label { display: flex; align-items: center; gap: 6px; }
.controls input[type=range] { flex: 1; }
.readout { font-size: 13px; color: #333; min-height: 1.4em; }
.legend { margin: 10px 0; font-size: 12px; }
.legend .row { display: flex; align-items: center; gap: 6px; margin: 2px 0; }
.legend .swatch { width: 22px; height: 12px; border: 1px solid #999; flex: none; }
.legend .bar { display: flex; height: 12px; border: 1px solid #999; }
.legend .bar span { flex: 1; }
.legend .ticks { display: flex; justify-content: space-between; }
table { border-collapse: collapse; font-size: 12px; margin: 6px 0; }
td, th { padding: 1px 8px 1px 0; text-align: right; }
td:first-child, th:first-child { text-align: left; }
.pass { color: #1b7a2f; } .fail { color: #b00020; font-weight: bold; }
#view { position: relative; min-width: 0; }
#view canvas.three { display: block; width: 100%; height: 100%; touch-action: none; }
#reset { position: absolute; top: 10px; right: 10px; font: inherit; font-size: 12px; }
#patch-panel { position: absolute; right: 10px; bottom: 10px; width: 380px; background: rgba(255,255,255,0.96); border: 1px solid #bbb; border-radius: 6px; padding: 8px; }
#patch-panel .panel-title { font-size: 12px; margin-bottom: 4px; padding-right: 20px; }
#patch-panel canvas { width: 362px; height: 300px; display: block; }
#patch-panel .close { position: absolute; top: 4px; right: 6px; border: none; background: none; font-size: 16px; cursor: pointer; }
#note { position: absolute; left: 10px; bottom: 10px; font-size: 12px; color: #444; background: rgba(255,255,255,0.8); padding: 2px 6px; }
`;
