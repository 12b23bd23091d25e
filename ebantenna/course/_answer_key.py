"""Expected answers of the exercises and their tolerances: ebantenna.course's key.

Written by ``docs/_tools/make_answer_key.py`` from the worked solutions in
``docs/exercises/solutions/``; do not edit by hand. The test suite checks that it equals what the
solutions compute.
"""

ANSWER_KEY = {
    'ex01_element': {
        'M11': {
            'value': 156.0, 'kind': 'abs', 'width': 1e-06,
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
        'M14': {
            'value': -13.0, 'kind': 'abs', 'width': 1e-06,
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
    },
    'ex02_assembly': {
        'n_typos_K1': {
            'value': 4.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'a count of matrix entries'
            ),
        },
        'K33': {
            'value': 5130.844444444443, 'kind': 'rel', 'width': 1e-09,
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
        'M33': {
            'value': 0.003888114285714285, 'kind': 'rel', 'width': 1e-09,
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
    },
    'ex03_convergence': {
        'order_mode1': {
            'value': 3.9993465364120637, 'kind': 'abs', 'width': 0.01,
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'order_mode2': {
            'value': 3.9968542559410154, 'kind': 'abs', 'width': 0.01,
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'error64_mode1': {
            'value': 1.2103273938635084e-09, 'kind': 'rel', 'width': 0.01,
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' nine-digit difference by up to about 1 %'
            ),
        },
    },
    'ex04_peak': {
        'a_peak': {
            'value': 0.7834444726531127, 'kind': 'abs', 'width': 0.001,
            'reason': (
                'the maximum is flat: a search on a 1e-3 grid or a bounded optimiser find it '
                'within 1e-3 L'
            ),
        },
        'f_peak': {
            'value': 87.00222073554554, 'kind': 'rel', 'width': 0.0001,
            'reason': (
                'at a flat maximum an error of 1e-3 L in the place changes the frequency by far '
                'less than 1e-4'
            ),
        },
        'a_peak_two_elements': {
            'value': 0.8381780391691234, 'kind': 'abs', 'width': 0.001,
            'reason': (
                'the maximum is flat: a search on a 1e-3 grid or a bounded optimiser find it '
                'within 1e-3 L'
            ),
        },
        'a_twin': {
            'value': 0.8936312959970132, 'kind': 'abs', 'width': 0.001,
            'reason': (
                'any root-finder (or a 1e-3 grid) on f(a) - f(0.7 L) beyond the maximum'
            ),
        },
    },
    'ex05_decay': {
        'tau_hand_ms': {
            'value': 80.92289300356806, 'kind': 'rel', 'width': 0.01,
            'reason': (
                'the window (from 10 to 30 ms, up to 5 to 20 times the noise) moves it by up to '
                '0.7 %'
            ),
        },
        'tau_fit_ms': {
            'value': 80.29360595580401, 'kind': 'rel', 'width': 0.001,
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by < '
                '0.01 %'
            ),
        },
        'a_fit': {
            'value': 4.992381411876605, 'kind': 'rel', 'width': 0.001,
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by < '
                '0.01 %'
            ),
        },
    },
    'ex06_svm_dual': {
        'w1': {
            'value': 1.3635099571974862, 'kind': 'abs', 'width': 0.001,
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'w2': {
            'value': 1.1144987763321594, 'kind': 'abs', 'width': 0.001,
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'b': {
            'value': 0.24888320957832594, 'kind': 'abs', 'width': 0.001,
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'n_support': {
            'value': 6.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'a count: multipliers above 1e-6'
            ),
        },
        'n_updates': {
            'value': 6.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'reference_smo on X X^T with tol=1e-8 takes the same steps'
            ),
        },
    },
    'ex07_backprop': {
        'loss': {
            'value': 0.998509052735973, 'kind': 'rel', 'width': 1e-09,
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
        'loss_after_step': {
            'value': 0.7320511563175731, 'kind': 'rel', 'width': 1e-09,
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
    },
    'ex08_filter_order': {
        'order': {
            'value': 13.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                "an integer: the next one above the formula's value"
            ),
        },
        'selectivity': {
            'value': 1.0767045376148512, 'kind': 'rel', 'width': 1e-06,
            'reason': (
                "the same closed formula; the edges' pre-warping is exact"
            ),
        },
        'radius_sos': {
            'value': 0.9976330748013186, 'kind': 'rel', 'width': 1e-06,
            'reason': (
                'roots of quadratics from the same design, to rounding'
            ),
        },
        'n_coefficients_ba': {
            'value': 27.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'a count: the denominator of a 26-pole filter'
            ),
        },
    },
    'ex09_mesh_budget': {
        'n_predicted': {
            'value': 18.0, 'kind': 'abs', 'width': 2.0,
            'reason': (
                'rounding the predicted mesh up or to the nearest, from the observed order or '
                'from exactly 4, moves it by an element or two'
            ),
        },
        'n_needed': {
            'value': 18.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'a count: the smallest mesh that meets the budget'
            ),
        },
        'error_needed': {
            'value': 9.38461609429897e-05, 'kind': 'rel', 'width': 0.01,
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' error of 1e-4 by far less than 1 %'
            ),
        },
    },
    'ex10_fifo': {
        'samples_after_50ms': {
            'value': 50.0, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'one sample more or less, as the 50 ms wait starts between two samples'
            ),
        },
        'arrived_while_reading': {
            'value': 30.0, 'kind': 'abs', 'width': 5.0,
            'reason': (
                'the virtual clock advances with every transfer: fewer or more reads than here '
                'move it by a few samples'
            ),
        },
        'overflow_count': {
            'value': 1024.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                "the FIFO's size in bytes"
            ),
        },
        'lost': {
            'value': 301.0, 'kind': 'abs', 'width': 5.0,
            'reason': (
                'the virtual clock advances with every transfer: fewer or more reads than here '
                'move it, by up to five samples'
            ),
        },
        'gap_ms': {
            'value': 302.13, 'kind': 'abs', 'width': 5.0,
            'reason': (
                'the virtual clock advances with every transfer: fewer or more reads than here '
                'move it, by up to five milliseconds'
            ),
        },
        'period_us': {
            'value': 1002.5062656641609, 'kind': 'rel', 'width': 1e-09,
            'reason': (
                'the middle of the bracket of a 5 % rate tolerance: rounding only'
            ),
        },
    },
    'ex11_rbf_cancellation': {
        'true': {
            'value': 23.06611976803216, 'kind': 'rel', 'width': 1e-12,
            'reason': (
                'a sum of five squares: only the last digits depend on the order'
            ),
        },
        'bound_1e6': {
            'value': 0.000770114384047907, 'kind': 'rel', 'width': 1e-06,
            'reason': (
                'the formula of the hint; norms summed in any order'
            ),
        },
        'error_1e6': {
            'value': 7.225502377166532e-05, 'kind': 'factor', 'width': 10.0,
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'error_1e6_sums': {
            'value': 1.2420032962709173e-05, 'kind': 'factor', 'width': 10.0,
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'direct_error_1e6': {
            'value': 3.4231310581346885e-11, 'kind': 'factor', 'width': 10.0,
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'libsvm_drift_1e6': {
            'value': 0.00023348828969863993, 'kind': 'factor', 'width': 3.0,
            'reason': (
                'scikit-learn versions and BLAS libraries round the training kernel differently'
            ),
        },
    },
    'ex12_splits': {
        'chance': {
            'value': 0.2, 'kind': 'abs', 'width': 0.005,
            'reason': (
                'one over the number of materials, rounded to two digits'
            ),
        },
        'seen_random': {
            'value': 1.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'seen_grouped': {
            'value': 0.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'accuracy_random': {
            'value': 0.5666666666666667, 'kind': 'abs', 'width': 0.035,
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_grouped': {
            'value': 0.26666666666666666, 'kind': 'abs', 'width': 0.035,
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_rigid': {
            'value': 0.13333333333333333, 'kind': 'abs', 'width': 0.035,
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
    },
    'ex13_mode_curves': {
        'spread_f1_pct': {
            'value': 1.3039112296082234, 'kind': 'rel', 'width': 0.1,
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'spread_f2_pct': {
            'value': 1.1667705460231659, 'kind': 'rel', 'width': 0.1,
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'repeat_pct': {
            'value': 0.3336783516459052, 'kind': 'rel', 'width': 0.1,
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'curve_accuracy': {
            'value': 0.7, 'kind': 'abs', 'width': 0.03,
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' 80'
            ),
        },
        'n_correct': {
            'value': 56.0, 'kind': 'abs', 'width': 2.0,
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' 80'
            ),
        },
        'n_test': {
            'value': 80.0, 'kind': 'abs', 'width': 0.0,
            'reason': (
                'the held-out recordings of the seeded grouped split'
            ),
        },
        'distance_cm': {
            'value': 0.7345028164617753, 'kind': 'rel', 'width': 0.1,
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'svm_accuracy': {
            'value': 0.5, 'kind': 'abs', 'width': 0.03,
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' 80'
            ),
        },
        'bins_per_cm': {
            'value': 1.8079266207403784, 'kind': 'rel', 'width': 0.1,
            'reason': (
                'a jump threshold of 5 to 20 bins, or another peak interpolation, moves the '
                'median by a few per cent'
            ),
        },
        'metals_smooth_from_cm': {
            'value': 15.0, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'metals_smooth_to_cm': {
            'value': 27.0, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_from_cm': {
            'value': 14.000000000000002, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_to_cm': {
            'value': 32.0, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'restrikes_median': {
            'value': 17.0, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
        'restrikes_max': {
            'value': 74.0, 'kind': 'abs', 'width': 1.0,
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
    },
    'ex14_kalman': {
        'k_steady': {
            'value': 0.04876562255935639, 'kind': 'rel', 'width': 0.0001,
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'sigma_steady': {
            'value': 0.04416587939093092, 'kind': 'rel', 'width': 0.0001,
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'rms_raw': {
            'value': 0.1984470938164844, 'kind': 'rel', 'width': 0.001,
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_filtered': {
            'value': 0.0476865932120654, 'kind': 'rel', 'width': 0.001,
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_small': {
            'value': 0.08693839303393334, 'kind': 'rel', 'width': 0.001,
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_large': {
            'value': 0.09734556997372883, 'kind': 'rel', 'width': 0.001,
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
    },
}
