// Conveniences on top of the declarations (--pre-js): shapes the page wants that are plain
// re-arrangements of what the core returns, never colour science.
Module['onRuntimeInitialized'] = function () {
  var M = Module;
  var flat = function (rows, key, Type) { return (Type || Float64Array).from([].concat.apply([], rows.map(function (r) { return r[key]; }))); };

  /// listCameras() -> [{id, name}] (name: the id with spaces, "Canon EOS 5D Mark II").
  M.listCameras = function () {
    return M.cameraNames().map(function (id) { return { id: id, name: id.split('_').join(' ') }; });
  };

  /// sampleChart(raw, layout, corners, options?) -> ChartSample plus its patches as columns:
  /// ids, RGB (the means, 3N), std (3N), n (Int32Array N), saturated_fraction (3N), flags
  /// (string[][]), centres (2N), patch_quads (8N), sample_quads (8N).
  var sampleChart = M.sampleChart;
  M.sampleChart = function () {
    var s = sampleChart.apply(null, arguments), p = s.patches;
    s.ids = p.map(function (q) { return q.id; });
    s.flags = p.map(function (q) { return q.flags; });
    s.RGB = flat(p, 'mean'); s.std = flat(p, 'std'); s.n = flat(p, 'n', Int32Array);
    s.saturated_fraction = flat(p, 'saturated_fraction'); s.centres = flat(p, 'centre');
    s.patch_quads = flat(p, 'quad'); s.sample_quads = flat(p, 'sample_quad');
    return s;
  };
  M.sampleChart.overloadTable = sampleChart.overloadTable;  // embind's arity dispatch looks it up by name

  /// evaluateProfile(profile JSON text, rgb, xyz, ids) -> {profile, estimated (3N),
  /// metrics, same_data_as_training (the training digest matches these patches)}.
  M.evaluateProfile = function (profile, rgb, xyz, ids) {
    // (a profile with a linearisation stage takes stored values: profilePredict linearises them)
    var p = M.profileFromJson(profile), estimated = M.profilePredict(profile, rgb);
    return { profile: p, estimated: estimated, metrics: M.evaluate(estimated, xyz, p.colorimetry.white),
      same_data_as_training: M.trainingDigest(ids, rgb, xyz) === p.training.digest };
  };
};
