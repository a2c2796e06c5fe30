# soak_memory.awk — how much a soaked lab's resident memory grew after the warm-up.
#
#   awk -v t0=START -v warm=SECONDS -v min=N [-v by_scene=1] -f bench/soak_memory.awk SAMPLES
#
# SAMPLES: one line per sample, "TIME RSS_KIB [SCENE]" (TIME in seconds, as `date +%s.%N` gives).
# Samples before t0 + warm (the warm-up) only count for rss_start_kib and rss_peak_kib.
#
# Like is compared with like. Resident memory depends on the scene variant loaded (lab 4 with every
# shadow switched off is about 115 MB lighter than with its own scene) and, in steps of a few MB, on what
# was loaded before it (lab 4's scene sits at 288 MB after the shadowless variant, 292-303 MB after
# the translucent one): a figure from one variant's samples moves with which of those steps fell at
# the start and at the end. So with by_scene=1 every sample is divided by the median of its own
# variant's samples (its usual level), and the figure uses all of them:
#
#   growth_pct = 100 * (median of the ratios in the last quarter of the time after the warm-up
#                       / median of the ratios in the first quarter  - 1)
#
# A leak adds to every variant and shows in every ratio; a variant loaded more often at one end
# than at the other does not. Each quarter takes at least 5 samples (the first or last 5 when its
# time holds fewer). Without by_scene all samples are one variant: the same as comparing medians.
# For the record the line also gives the most-seen variant alone, in KiB (the older figure).
# Exit 1 with the reason when fewer than `min` samples follow the warm-up.

function median(a, n,   i, j, t, b) {  # of a[1..n]; a is left alone
  for (i = 1; i <= n; i++) b[i] = a[i]
  for (i = 2; i <= n; i++) { t = b[i]; for (j = i - 1; j >= 1 && b[j] > t; j--) b[j + 1] = b[j]; b[j + 1] = t }
  return (n % 2) ? b[(n + 1) / 2] : (b[n / 2] + b[n / 2 + 1]) / 2
}

{
  t = $1 - t0
  if (t < 0) next
  n_all++
  if (n_all == 1) first = $2
  if ($2 > peak) peak = $2
  if (t < warm) next
  n++; time[n] = t; rss[n] = $2; scene[n] = by_scene ? $3 : "-"
  seen[scene[n]]++; of[scene[n], seen[scene[n]]] = $2
  if (n == 1 || $2 < low) low = $2
}

END {
  if (n < min) { printf "too few samples after the warm-up (%d, at least %d)", n, min; exit 1 }
  # Each variant's usual level, and every sample as a ratio to it.
  variants = 0
  for (s in seen) {
    variants++
    for (i = 1; i <= seen[s]; i++) v[i] = of[s, i]
    level[s] = median(v, seen[s])
    if (seen[s] > best_n) { best_n = seen[s]; best = s }
  }
  for (i = 1; i <= n; i++) ratio[i] = rss[i] / level[scene[i]]
  # The first and the last quarter of the time after the warm-up, at least 5 samples each.
  quarter = (time[n] - time[1]) / 4
  k = (n < 5) ? n : 5
  for (i = 1; i <= n; i++) if (time[i] < time[1] + quarter || na < k) { na++; a[na] = ratio[i] }
  for (i = n; i >= 1; i--) if (time[i] > time[n] - quarter || nb < k) { nb++; b[nb] = ratio[i] }
  growth = 100 * (median(b, nb) / median(a, na) - 1)
  printf "rss_start_kib=%d rss_min_kib=%d rss_peak_kib=%d growth_pct=%.3f samples=%d quarters=%d/%d",
         first, low, peak, growth, n_all, na, nb
  if (!by_scene) { printf " rss_after_warmup_kib=%d rss_end_kib=%d", median(a, na) * level["-"], median(b, nb) * level["-"]; exit }
  # The most-seen variant alone (its first and last quarter of samples, at least 5): for the record.
  m = best_n; q = int(m / 4); if (q < 5) q = 5; if (q > m) q = m
  for (i = 1; i <= q; i++) { c[i] = of[best, i]; d[i] = of[best, m - q + i] }
  base = median(c, q); last = median(d, q)
  printf " variants=%d; most seen alone: scene=%s (%d samples) %d -> %d KiB, %+.3f %%",
         variants, best, m, base, last, 100 * (last - base) / base
}
