"""plot_campaign.py's tick and metric rules: every tick label at most 4 significant digits and
distinct from its neighbours, and round-off spreads not drawn as variation."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import plot_campaign  # noqa: E402


def significant_digits(text):
    mantissa = text.split("e")[0].lstrip("-").replace(".", "").lstrip("0")
    return len(mantissa)


class FourDigitTicks(unittest.TestCase):
    def test_labels_are_distinct_and_short(self):
        # Ranges of a rimless campaign's metrics (mean speed, final energy, work of friction), a
        # count, a round-off-sized quantity and a negative range.
        for lo, hi in [(1.488, 1.492), (9.8665, 9.879), (0.0246, 0.0407), (0, 2), (9e-14, 1.33e-12),
                       (-1, 0), (120, 122), (1000.0, 1000.4)]:
            ticks = [t for t in plot_campaign.FourDigitLocator().tick_values(lo, hi) if lo <= t <= hi]
            labels = [plot_campaign.TICKS(t, None) for t in ticks]
            self.assertGreaterEqual(len(ticks), 1, (lo, hi))
            self.assertEqual(len(set(labels)), len(labels), (lo, hi, labels))
            self.assertTrue(all(significant_digits(x) <= 4 for x in labels), (lo, hi, labels))

    def test_grid_values_are_written_with_four_digits(self):
        self.assertEqual(plot_campaign.tick_text("0.30000000000000004"), "0.3")
        self.assertEqual(plot_campaign.tick_text("both"), "both")


class VaryingMetrics(unittest.TestCase):
    def test_round_off_is_not_variation(self):
        # A multiplier equal to 12 digits at every point where it exists does not vary; blank
        # cells (no fixed point) alone are not variation either.
        self.assertFalse(plot_campaign.varies(["0.7277625407177563", "0.7277625407208538", ""], True))
        self.assertTrue(plot_campaign.varies(["0.7277", "0.7290", ""], True))
        self.assertFalse(plot_campaign.varies(["0", "0"], True))
        self.assertTrue(plot_campaign.varies(["stick", "slip"], False))

    def test_default_figure_draws_only_varying_numbers(self):
        rows = [{"gait": "stick", "speed": "1.1", "model": "rigid"}, {"gait": "slip", "speed": "1.5", "model": "rigid"}]
        self.assertEqual(plot_campaign.split_metrics(rows, ["gait", "speed", "model"]), (["speed"], []))
        self.assertEqual(plot_campaign.split_metrics(rows, ["gait", "speed"], keep_constant=True), (["speed"], ["gait"]))


if __name__ == "__main__":
    unittest.main()
