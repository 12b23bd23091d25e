"""Sealed answers of the exercises and their tolerances: ebantenna.course's key.

Written by ``docs/_tools/make_answer_key.py`` from the worked solutions in
``docs/exercises/solutions/``; do not edit by hand. Each answer is held as the salted hash of its
cell and its place in the cell (see :func:`ebantenna.course.seal`), not as a value. The test
suite checks that it seals what the solutions compute.
"""

ANSWER_KEY = {
    'ex01_element': {
        'M11': {
            'kind': 'abs', 'width': 1e-06,
            'salt': 'ex01_element/M11', 'offset': 0.0,
            'digest': '81293e9b6559eee572aa48a4982ac9d5',
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
        'M14': {
            'kind': 'abs', 'width': 1e-06,
            'salt': 'ex01_element/M14', 'offset': 0.0,
            'digest': '1ad81453d7ec1fe524249cfb4c9e50ce',
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
    },
    'ex02_assembly': {
        'n_typos_K1': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex02_assembly/n_typos_K1', 'offset': 0.0,
            'digest': 'd1a922220460dae33a7a7d16014dbd89',
            'reason': (
                'a count of matrix entries'
            ),
        },
        'K33': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex02_assembly/K33', 'offset': 0.40021514892578125,
            'digest': 'a23e5b04777b453bbf371e937c5f455d',
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
        'M33': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex02_assembly/M33', 'offset': 0.4328012466430664,
            'digest': 'f1f123a0d491b16dcfde038116ae8762',
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
    },
    'ex03_convergence': {
        'order_mode1': {
            'kind': 'abs', 'width': 0.01,
            'salt': 'ex03_convergence/order_mode1', 'offset': 0.9346536412063529,
            'digest': '58f0b5e20f25316fdc7a436f5e42ba51',
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'order_mode2': {
            'kind': 'abs', 'width': 0.01,
            'salt': 'ex03_convergence/order_mode2', 'offset': 0.6854255941015595,
            'digest': 'dc04f8de0f96335ccedeb017b57d352e',
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'error64_mode1': {
            'kind': 'rel', 'width': 0.01,
            'salt': 'ex03_convergence/error64_mode1', 'offset': 0.04588983044254746,
            'digest': '212ee979a527a4005897946cdcd89c5f',
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' nine-digit difference by up to about 1 %'
            ),
        },
    },
    'ex04_peak': {
        'a_peak_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_peak_cm', 'offset': 0.7555781224901921,
            'digest': '316ca94ea41b0045154e1fbbed4f8601',
            'reason': (
                'the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it '
                'within 1e-3 L (0.045 cm at most)'
            ),
        },
        'f_peak': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex04_peak/f_peak', 'offset': 0.1034362073551165,
            'digest': '66d9d0056cbb98ea9957b613b683515a',
            'reason': (
                'at a flat maximum an error of 1e-3 L in the place changes the frequency by far '
                'less than 1e-4'
            ),
        },
        'a_peak_two_elements_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_peak_two_elements_cm', 'offset': 0.5424313352979198,
            'digest': 'bdf3e672f39788ff4b8a105329b4d716',
            'reason': (
                'the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it '
                'within 1e-3 L (0.045 cm at most)'
            ),
        },
        'a_twin_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_twin_cm', 'offset': 0.9050367976105917,
            'digest': 'cbc7a3ec1efbafe765aee217c2e32a01',
            'reason': (
                'any root-finder (or a 1e-3 L grid) on f(a) - f(twin_of L) beyond the maximum'
            ),
        },
    },
    'ex05_decay': {
        'tau_hand_ms': {
            'kind': 'rel', 'width': 0.04,
            'salt': 'ex05_decay/tau_hand_ms', 'offset': 0.6257251684252338,
            'digest': 'adf6e9b56d1ab027458382c719098cb3',
            'reason': (
                'the window (from 10 to 30 ms, up to 5 to 20 times the noise) moves it by up to 4'
                ' %'
            ),
        },
        'tau_fit_ms': {
            'kind': 'rel', 'width': 0.002,
            'salt': 'ex05_decay/tau_fit_ms', 'offset': 0.6514187398470312,
            'digest': '1bd9394003884501dd8a80d73bc6e2ee',
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by up to'
                ' 0.2 %'
            ),
        },
        'a_fit': {
            'kind': 'rel', 'width': 0.002,
            'salt': 'ex05_decay/a_fit', 'offset': 0.1522916153630831,
            'digest': '2c615a1111d43b81bdb9eca5fa1454fd',
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by up to'
                ' 0.2 %'
            ),
        },
    },
    'ex06_svm_dual': {
        'w1': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/w1', 'offset': 0.5099571974863011,
            'digest': '39addd4ac543020f3400baf53173bac2',
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'w2': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/w2', 'offset': 0.49877633215942296,
            'digest': '396d6095176c60b740b80e247c78b4e8',
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'b': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/b', 'offset': 0.8832095783259319,
            'digest': 'ff7104ceda7b20ac26f3823a071d5ae5',
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'n_support': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex06_svm_dual/n_support', 'offset': 0.0,
            'digest': '046955804fb8427e13195cc375418321',
            'reason': (
                'a count: multipliers above 1e-6'
            ),
        },
        'dual_objective': {
            'kind': 'abs', 'width': 0.0001,
            'salt': 'ex06_svm_dual/dual_objective', 'offset': 0.3885650054362486,
            'digest': '55417b514e2c6f3941194fc9f38825e7',
            'reason': (
                "a solver stopped at a duality gap g is within g of the optimum: SLSQP's below "
                "1e-5 (about 1e-14 here), SMO's n C tol = 3e-7 at tol=1e-8"
            ),
        },
    },
    'ex07_backprop': {
        'loss': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex07_backprop/loss', 'offset': 0.16885614045895636,
            'digest': '3dd960e7e6ad0603fb96b7357713da0f',
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
        'loss_after_step': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex07_backprop/loss_after_step', 'offset': 0.37298130989074707,
            'digest': 'd5e97e89044c35c01a428642eca56fdc',
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
    },
    'ex08_filter_order': {
        'order': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex08_filter_order/order', 'offset': 0.0,
            'digest': '43104c776848f3c30df17a7460ca0383',
            'reason': (
                "an integer: the next one above the formula's value"
            ),
        },
        'selectivity': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex08_filter_order/selectivity', 'offset': 0.9852506183378864,
            'digest': '2be5d76aa509750f6807c2436314eb82',
            'reason': (
                "the same closed formula; the edges' pre-warping is exact"
            ),
        },
        'radius_sos': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex08_filter_order/radius_sos', 'offset': 0.2703907721215728,
            'digest': '41cdad0f69778bf157bf305882ee44e8',
            'reason': (
                'roots of quadratics from the same design, to rounding'
            ),
        },
        'n_coefficients_ba': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex08_filter_order/n_coefficients_ba', 'offset': 0.0,
            'digest': '6c32698ceaee98486990b560eff29097',
            'reason': (
                'a count: the denominator of a 26-pole filter'
            ),
        },
    },
    'ex09_mesh_budget': {
        'n_predicted': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex09_mesh_budget/n_predicted', 'offset': 0.0,
            'digest': '7af03efba5cd12d439bb48d768ffa044',
            'reason': (
                'a count: up or to the nearest, from the observed order or exactly 4, it is 18 '
                '(17.9 and 18.0 before rounding)'
            ),
        },
        'n_needed': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex09_mesh_budget/n_needed', 'offset': 0.0,
            'digest': 'e7251487c725068bce3e05729d44edcb',
            'reason': (
                'a count: the smallest mesh that meets the budget'
            ),
        },
        'error_needed': {
            'kind': 'rel', 'width': 0.01,
            'salt': 'ex09_mesh_budget/error_needed', 'offset': 0.2593237423436676,
            'digest': '8a381adf45ae50168d5b8f11155cbca6',
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' error of 1e-4 by far less than 1 %'
            ),
        },
    },
    'ex10_fifo': {
        'samples_after_50ms': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/samples_after_50ms', 'offset': 0.0,
            'digest': '912d4d4593f7e07cdea852a438f53326',
            'reason': (
                'one sample more or less, as the 50 ms wait starts between two samples'
            ),
        },
        'arrived_while_reading': {
            'kind': 'abs', 'width': 2.0,
            'salt': 'ex10_fifo/arrived_while_reading', 'offset': 0.5,
            'digest': '8692e5ed873d2f993dbd9833b81546f3',
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock move it by a '
                'sample or two'
            ),
        },
        'overflow_count': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex10_fifo/overflow_count', 'offset': 0.0,
            'digest': '409ee29213885d6c98142c36cbd9e1ad',
            'reason': (
                "the FIFO's size in bytes"
            ),
        },
        'lost': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/lost', 'offset': 0.0,
            'digest': 'd4b604fa58fc1aeac728bc6a3e6e3f70',
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock between the '
                "driver's calls move it by one sample"
            ),
        },
        'gap_ms': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/gap_ms', 'offset': 0.6200000000001182,
            'digest': '83bff6a71e3a748c333de01a83498118',
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock between the '
                "driver's calls move it by under 1 ms"
            ),
        },
        'period_us': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex10_fifo/period_us', 'offset': 0.7451257705688477,
            'digest': 'af49e4ea55fb7e33ce3a245de2864251',
            'reason': (
                'the middle of the bracket of a 5 % rate tolerance: rounding only'
            ),
        },
    },
    'ex11_rbf_cancellation': {
        'true': {
            'kind': 'rel', 'width': 1e-12,
            'salt': 'ex11_rbf_cancellation/true', 'offset': 0.49609375,
            'digest': '14eac3b50275c58a13464ce7ae617b90',
            'reason': (
                'a sum of five squares: only the last digits depend on the order'
            ),
        },
        'bound_1e6': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex11_rbf_cancellation/bound_1e6', 'offset': 0.08104880806058645,
            'digest': 'b39a9b594eb1de3c4772811babff18a2',
            'reason': (
                'the formula of the hint; norms summed in any order'
            ),
        },
        'error_1e6': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/error_1e6', 'offset': 0.8588680482515967,
            'digest': '4c5e3d94ef5d546914494f8de41ce97d',
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'error_1e6_sums': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/error_1e6_sums', 'offset': 0.09412274845760749,
            'digest': 'f48e090e75e180043edca1e1d902df51',
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'direct_error_1e6': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/direct_error_1e6', 'offset': 0.5344235268723541,
            'digest': '7a4f53e3669a3350b0421d5b340eed50',
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'libsvm_drift_1e6': {
            'kind': 'factor', 'width': 3.0,
            'salt': 'ex11_rbf_cancellation/libsvm_drift_1e6', 'offset': 0.3882349400674139,
            'digest': '5f8012db7e517c3da963d22055aa691b',
            'reason': (
                'scikit-learn versions and BLAS libraries round the training kernel differently'
            ),
        },
    },
    'ex12_splits': {
        'chance': {
            'kind': 'abs', 'width': 0.005,
            'salt': 'ex12_splits/chance', 'offset': 0.0,
            'digest': 'd229e0b5ef712cd3e098de1aae0dc7fa',
            'reason': (
                'one over the number of materials, rounded to two digits'
            ),
        },
        'seen_random': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex12_splits/seen_random', 'offset': 0.0,
            'digest': '9f3422039f85ec9842c5a244d100839d',
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'seen_grouped': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex12_splits/seen_grouped', 'offset': 0.0,
            'digest': '472a50b70e59b1c98d1fa2d92d05e162',
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'accuracy_random': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_random', 'offset': 0.1904761904761898,
            'digest': 'afffbbbd33acbbc9c33a816cbe2d6e09',
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_grouped': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_grouped', 'offset': 0.6190476190476186,
            'digest': 'af4f0ea999b28e4cac893e2382d73536',
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_rigid': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_rigid', 'offset': 0.8095238095238093,
            'digest': '0fce38d0013e1961d2330816720586d3',
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
    },
    'ex13_mode_curves': {
        'spread_f1_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/spread_f1_pct', 'offset': 0.5186701495959696,
            'digest': '063c02928969391d3e61956bcbf1a5b5',
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'spread_f2_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/spread_f2_pct', 'offset': 0.46392331462030656,
            'digest': 'c96c0ce77426cc8115ba21c2fe78bba8',
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'repeat_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/repeat_pct', 'offset': 0.5826461917199062,
            'digest': 'ed717752034d46ae4b9ff7db2b91dd39',
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'curve_accuracy': {
            'kind': 'abs', 'width': 0.03,
            'salt': 'ex13_mode_curves/curve_accuracy', 'offset': 0.33333333333333215,
            'digest': '74de3d24f26de0115281add9434a045a',
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' 80'
            ),
        },
        'n_correct': {
            'kind': 'abs', 'width': 2.0,
            'salt': 'ex13_mode_curves/n_correct', 'offset': 0.0,
            'digest': 'e12042748737195cf7414ff454168367',
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' 80'
            ),
        },
        'n_test': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex13_mode_curves/n_test', 'offset': 0.0,
            'digest': 'cd19d38cfbb598d4614ed26306d202a3',
            'reason': (
                'the held-out recordings of the seeded grouped split'
            ),
        },
        'distance_cm': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/distance_cm', 'offset': 0.0713749176366103,
            'digest': '01504f62b77adf93ac88efc7d42c2e91',
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'svm_accuracy': {
            'kind': 'abs', 'width': 0.03,
            'salt': 'ex13_mode_curves/svm_accuracy', 'offset': 0.6666666666666679,
            'digest': '3bad5613a45bf8d1cc76a6ae1692e0de',
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' 80'
            ),
        },
        'bins_per_cm': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/bins_per_cm', 'offset': 0.6205180050168391,
            'digest': 'b26f1cd5724c8992bc06ac5a08633c07',
            'reason': (
                'a jump threshold of 5 to 20 bins, or another peak interpolation, moves the '
                'median by a few per cent'
            ),
        },
        'metals_smooth_from_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/metals_smooth_from_cm', 'offset': 0.0,
            'digest': '36086f0e0102652fe7c579f89b1a877d',
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'metals_smooth_to_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/metals_smooth_to_cm', 'offset': 0.0,
            'digest': '8464161b7da892b06d2b05b6501e1d7e',
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_from_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/pvc_smooth_from_cm', 'offset': 1.7763568394002505e-15,
            'digest': 'cde5be86e9e023dfa3fb106c9f76a89d',
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_to_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/pvc_smooth_to_cm', 'offset': 0.0,
            'digest': 'b703de7905f5fc721a69a652c39e2f9a',
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'restrikes_median': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/restrikes_median', 'offset': 0.0,
            'digest': 'e1d577d79d011bb8cd7b72837606bbcd',
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
        'restrikes_max': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/restrikes_max', 'offset': 0.0,
            'digest': '2399cbdfac450d858c2a5b959af66619',
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
    },
    'ex14_kalman': {
        'k_steady': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex14_kalman/k_steady', 'offset': 0.21368881432863418,
            'digest': 'f6a3cdf107a6de58613a1aaa82c1d868',
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'sigma_steady': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex14_kalman/sigma_steady', 'offset': 0.5324524350362481,
            'digest': 'a8e32220b92e45a37d99b7e672b80ec1',
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'rms_raw': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_raw', 'offset': 0.5760069368964196,
            'digest': 'c54db0527a28cbc06a22458ff41d67e1',
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_filtered': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_filtered', 'offset': 0.41682088111201665,
            'digest': 'e46e201217da3e61159dd2ef1996c1ba',
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_small': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_q_small', 'offset': 0.665944202769424,
            'digest': 'd6492e472ea4174f373be75e86e57f1a',
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_large': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_q_large', 'offset': 0.6768838725638489,
            'digest': '7358f7e11109000c7f4e6582aade0c22',
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
    },
    'ex15_design_effect': {
        'accuracy': {
            'kind': 'abs', 'width': 0.0025,
            'salt': 'ex15_design_effect/accuracy', 'offset': 0.0,
            'digest': '7dff7b2e23c0b2ba337af04126c4e35e',
            'reason': (
                'a count of right answers out of 200: half of one in 200'
            ),
        },
        'rec_low': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/rec_low', 'offset': 0.37960415678207937,
            'digest': 'dd8902668709ba137c19812e0bcfd79a',
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'rec_high': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/rec_high', 'offset': 0.08752746625418695,
            'digest': 'b60f93f89fdda92ed36787db2ed71c11',
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'icc': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/icc', 'offset': 0.16320544795416936,
            'digest': 'd9e9a173cd5b84435dfdf7117a47a0d7',
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'deff_icc': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/deff_icc', 'offset': 0.7292554981941066,
            'digest': 'f7dcaa2e534b718123feb4beaa439798',
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'deff': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/deff', 'offset': 0.04452423035581887,
            'digest': 'a64368363f3a899a22ebb2e6acb4f232',
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'n_eff': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/n_eff', 'offset': 0.47993841187417274,
            'digest': 'f845118bef977c93e7cae796b3927d27',
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'eff_low': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/eff_low', 'offset': 0.30837663854390485,
            'digest': 'ea9ee0aa0ce82d3dd1a9eb36036583a6',
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'eff_high': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/eff_high', 'offset': 0.2649888226192161,
            'digest': '14f7696fb317b2e255ea5df6960494c7',
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'boot_low': {
            'kind': 'abs', 'width': 0.0125,
            'salt': 'ex15_design_effect/boot_low', 'offset': 0.7999999999999972,
            'digest': '3dee1b2668bc8d0384d006f9af4635e1',
            'reason': (
                "another seed's 10000 resamples move an end by at most 2 steps of 1/200 (4 sd of "
                'a percentile), half a step for quantile conventions'
            ),
        },
        'boot_high': {
            'kind': 'abs', 'width': 0.0125,
            'salt': 'ex15_design_effect/boot_high', 'offset': 0.5999999999999943,
            'digest': 'e729c5262286f1395807ead549d7f181',
            'reason': (
                "another seed's 10000 resamples move an end by at most 2 steps of 1/200 (4 sd of "
                'a percentile), half a step for quantile conventions'
            ),
        },
        'coverage_recording': {
            'kind': 'abs', 'width': 0.0005,
            'salt': 'ex15_design_effect/coverage_recording', 'offset': 0.0,
            'digest': '18a206141937325ad7d7c555087d3729',
            'reason': (
                "a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding "
                'or z = 1.96 flips none; half a design'
            ),
        },
        'coverage_deff': {
            'kind': 'abs', 'width': 0.0005,
            'salt': 'ex15_design_effect/coverage_deff', 'offset': 0.0,
            'digest': '33000531aa879e62105c824b4818c711',
            'reason': (
                "a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding "
                'or z = 1.96 flips none; half a design'
            ),
        },
    },
}
