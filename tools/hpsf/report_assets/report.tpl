{{%AUTOESCAPE context="HTML"}}{{!
  The page of `hpsf diff --html` and `hpsf golden check`: its structure only. ctemplate escapes every variable
  for the place it stands in (auto-escape); :none marks what the C++ built itself and must pass unchanged: the
  style, the script and the heatmap's data: URI, which the URL escaper would otherwise refuse.
}}<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="hpsf {{VERSION}}">
<title>{{TITLE}}</title>
<style>{{STYLE:none}}</style>
</head>
<body>
<header class="page">
<h1>{{TITLE}}</h1>
<p class="counts">{{ENTRY_COUNT}} {{ENTRY_NOUN}}:
{{#VERDICT_COUNT}}<span class="verdict {{VERDICT_CLASS}}">{{N}} {{VERDICT}}</span> {{/VERDICT_COUNT}}</p>
</header>
{{#SUMMARY}}
<table class="summary">
<thead><tr><th>case</th><th>verdict</th><th>judged metric</th></tr></thead>
<tbody>
{{#SUMMARY_ROW}}<tr><td><a href="#{{ANCHOR}}">{{TITLE}}</a></td>
<td><span class="verdict {{VERDICT_CLASS}}">{{VERDICT}}</span></td><td>{{METRIC}} {{VALUE}}</td></tr>
{{/SUMMARY_ROW}}
</tbody>
</table>
{{/SUMMARY}}
{{#ENTRY}}
<section class="entry" id="{{ANCHOR}}" data-width="{{SHOWN_WIDTH}}" data-height="{{SHOWN_HEIGHT}}"
  data-factor="{{FACTOR}}">
<h2><span class="verdict {{VERDICT_CLASS}}">{{VERDICT}}</span> {{TITLE}}</h2>
<p class="explanation">{{EXPLANATION}}</p>
<p class="facts">{{WIDTH}}&times;{{HEIGHT}}, channels {{CHANNELS}}; shown: {{SHOWN_CHANNELS}}{{#DOWNSAMPLED}}.
<strong>A and B are shown downsampled {{FACTOR}}&times; (box filter) to {{SHOWN_WIDTH}}&times;{{SHOWN_HEIGHT}}</strong>
to keep the page small; the metrics and the heatmap are computed at full resolution{{/DOWNSAMPLED}}.</p>
<div class="controls">
<label>exposure <input type="range" class="exposure" min="-8" max="8" step="0.25" value="0">
<output class="exposure-value">+0.00</output> stops</label>
<button type="button" class="exposure-reset">reset</button>
</div>
<div class="panels">
<figure style="width: {{PANEL_WIDTH}}px">
<canvas class="image a {{PANEL_PIXELATED}}" width="{{SHOWN_WIDTH}}" height="{{SHOWN_HEIGHT}}"
  data-pixels="{{A_PIXELS}}"></canvas>
<figcaption><b>A</b> {{A_LABEL}}</figcaption>
</figure>
<figure style="width: {{PANEL_WIDTH}}px">
<canvas class="image b {{PANEL_PIXELATED}}" width="{{SHOWN_WIDTH}}" height="{{SHOWN_HEIGHT}}"
  data-pixels="{{B_PIXELS}}"></canvas>
<figcaption><b>B</b> {{B_LABEL}}</figcaption>
</figure>
<figure style="width: {{HEATMAP_WIDTH}}px">
<img class="heatmap {{PANEL_PIXELATED}}" src="{{HEATMAP_URI:none}}"
  width="{{HEATMAP_WIDTH}}" height="{{HEATMAP_HEIGHT}}" alt="error heatmap of {{TITLE}}">
<figcaption><b>|A&minus;B|</b> largest over the colour channels, per pixel
{{#HEATMAP_LEGEND}}<span class="legend"><span>0</span><span class="ramp"></span><span>{{HEATMAP_TOP}}{{#HEATMAP_CLIPPED}}
and above (max {{HEATMAP_LARGEST}}){{/HEATMAP_CLIPPED}}</span></span>{{/HEATMAP_LEGEND}}</figcaption>
</figure>
</div>
<div class="lower">
<div class="compare" style="width: {{WIPE_WIDTH}}px">
<div class="wipe" title="drag to move the wipe">
<canvas class="wipe-b {{WIPE_PIXELATED}}" width="{{SHOWN_WIDTH}}" height="{{SHOWN_HEIGHT}}"></canvas>
<canvas class="wipe-a {{WIPE_PIXELATED}}" width="{{SHOWN_WIDTH}}" height="{{SHOWN_HEIGHT}}"></canvas>
<div class="wipe-line"></div>
<span class="wipe-label left">A</span><span class="wipe-label right">B</span>
</div>
<div class="compare-controls">
<label>wipe A | B <input type="range" class="wipe-position" min="0" max="100" step="0.1" value="50"></label>
<button type="button" class="flip">show A</button>
<output class="readout">point at the image for its values</output>
</div>
</div>
<div class="tables">
<table class="metrics">
<caption>metrics of A against B</caption>
<thead><tr><th>metric</th><th>value</th><th>note</th></tr></thead>
<tbody>
{{#METRIC_ROW}}<tr class="{{ROW_CLASS}}"><th>{{NAME}}</th><td>{{VALUE}}</td><td>{{NOTE}}</td></tr>
{{/METRIC_ROW}}
</tbody>
</table>
<table class="metadata">
<caption>hpsf: metadata</caption>
<thead><tr><th>key</th><th>A</th><th>B</th></tr></thead>
<tbody>
{{#METADATA_SAME}}<tr><td colspan="3" class="same">the same
{{#METADATA_COUNT}}({{KEYS}} keys){{/METADATA_COUNT}}</td></tr>
{{/METADATA_SAME}}
{{#METADATA_ROW}}<tr><th>{{KEY}}</th><td class="{{A_CLASS}}">{{A}}</td><td class="{{B_CLASS}}">{{B}}</td></tr>
{{/METADATA_ROW}}
</tbody>
</table>
{{#EXTRA}}
<table class="extra">
<caption>{{EXTRA_CAPTION}}</caption>
<tbody>
{{#EXTRA_ROW}}<tr><th>{{KEY}}</th><td>{{VALUE}}</td></tr>
{{/EXTRA_ROW}}
</tbody>
</table>
{{/EXTRA}}
</div>
</div>
</section>
{{/ENTRY}}
<footer>Written by hpsf {{VERSION}}. Self-contained: the images, style and script are in this file.</footer>
<script>
// Installed before the report's script, so a script that fails to parse or throws is recorded in the DOM, where
// a headless browser test reads it (tools/testing/html_report_chromium.cmake).
window.addEventListener('error', function (event) {
  var errors = document.body.dataset.errors ? document.body.dataset.errors + '\n' : '';
  document.body.dataset.errors = errors + event.message + ' (line ' + event.lineno + ')';
});
window.addEventListener('unhandledrejection', function (event) {
  var errors = document.body.dataset.errors ? document.body.dataset.errors + '\n' : '';
  document.body.dataset.errors = errors + 'unhandled rejection: ' + event.reason;
});
</script>
<script>{{SCRIPT:none}}</script>
</body>
</html>
