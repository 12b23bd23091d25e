"""Sealed answers of the exercises and their tolerances: ebantenna.course's key.

Written by ``docs/_tools/make_answer_key.py`` from the worked solutions in
``docs/exercises/solutions/``; do not edit by hand. Each answer is held as the stretched, salted
hashes of the cells within its tolerance (see :func:`ebantenna.course.seal`), not as a value.
The test suite checks that it seals what the solutions compute.
"""

ANSWER_KEY = {
    'ex01_element': {
        'M11': {
            'kind': 'abs', 'width': 1e-06,
            'salt': 'ex01_element/M11',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '3e960c2700cdc9ee', '4f3738c7e36dc34b', '6327658f68d401ce', '928f5fa3144de4ea',
                '9bf28253166b1fe5', '9e43a4fc28e02724', 'a2fb3914a54584fe', 'b728113988e2289e',
                'b7e2441e8d8f93ae', 'd6e7cba7e8939748', 'fe184402858130c8',
            ],
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
        'M14': {
            'kind': 'abs', 'width': 1e-06,
            'salt': 'ex01_element/M14',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '61b82e017e933c80', '76553c6bc7ad7d42', '7ab6a801fdb087a2', '7c69948b66880fcf',
                '88463ba3e9911eb4', '8a3e4fce92bb03e4', 'b2251242a26b2ba0', 'd2da277dc1adc2e0',
                'd8000d233e155f9e', 'dc747f243aa0e2ca', 'e1e545c55bd15b55',
            ],
            'reason': (
                'exact rational arithmetic gives an integer; 1e-6 admits a floating-point '
                'quadrature'
            ),
        },
    },
    'ex02_assembly': {
        'n_typos_K1': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex02_assembly/n_typos_K1',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '9af6efe38405f20b',
            ],
            'reason': (
                'a count of matrix entries'
            ),
        },
        'K33': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex02_assembly/K33',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0f17b781c93374eb', '234f6e7b56c79dd9', '5da1974531f11866', '64891d866aacf71a',
                '7f24ff1f20dcf070', '877c233d2a341a2c', 'ad3a947a5fa233ac', 'b973843350ec3b0b',
                'ce9c3bbf98c6d275', 'df6e81af37766b46', 'e17e83818ca7432d',
            ],
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
        'M33': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex02_assembly/M33',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '072b1a6387c435da', '3a33994c2c55c169', '48d6e243d06d482c', '4e6edba0446c57bb',
                '5720a6ad0057c15f', '5ec98ac66a0adbe1', '6c9779bc2044550f', '871d1e0bee1270e9',
                '8e3e6dd23517c69c', 'a80380d72ac27650', 'd62f868048491ce4',
            ],
            'reason': (
                'the same two terms added in any order: only the last of 16 digits can differ'
            ),
        },
    },
    'ex03_convergence': {
        'order_mode1': {
            'kind': 'abs', 'width': 0.01,
            'salt': 'ex03_convergence/order_mode1',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '20106388ec7166e7', '287596ec79da5226', '3106be744cce1dd1', '35943c3ece17555b',
                '4032288de0db1ffc', '5bf97461ad10320d', '68fb7d0065daf9a6', '7373e85ea07a829e',
                'b6da3e5648acc050', 'b7d752d5fdf4fe95', 'bd136896b14a434c',
            ],
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'order_mode2': {
            'kind': 'abs', 'width': 0.01,
            'salt': 'ex03_convergence/order_mode2',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '031aa8ff0f3780b7', '0399ff63f6705d3f', '1ba33aee8cb8cfb5', '238235e624555cc2',
                '2e033c94fa58e0c7', '399b8cee1ee1e71e', '53af9b6f1f6cca58', 'b15380097e1bb302',
                'ba16e8ca9cb885e0', 'd71c1544219d02be', 'e28f07f24cb6233f',
            ],
            'reason': (
                'the same meshes give the same order to many digits; 0.01 admits an own exact '
                'solver'
            ),
        },
        'error64_mode1': {
            'kind': 'rel', 'width': 0.01,
            'salt': 'ex03_convergence/error64_mode1',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '09ccf3b0ff0f254e', '485b20511a46baf3', '5e0d8211d07a9b57', '6f024f8384f1a2ca',
                '89e1e49d0d66febe', 'babd521e88834e0f', 'cc74319b2ae4746f', 'eab2fd3d1fcb284e',
                'ecc7adc16e50a2df', 'f9415f4966872184', 'fd19cda1bcd0c3fa',
            ],
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' nine-digit difference by up to about 1 %'
            ),
        },
    },
    'ex04_peak': {
        'a_peak_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_peak_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '338b93a0ea792aaf', '3551b9bad944f533', '56d221d5c365c307', '6b4bce4a18520e43',
                '6bcc97790dd4c892', '754369da79eb548a', '9c51b141b67c42c0', 'aa0c66f143524f2f',
                'bf1582800c81ef13', 'd7903ddc7b9be227', 'f3c87bbf26bd4ae1',
            ],
            'reason': (
                'the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it '
                'within 1e-3 L (0.045 cm at most)'
            ),
        },
        'f_peak': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex04_peak/f_peak',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '15f805ab3530019b', '1bc62f10beee81a8', '27efb67ed751a5fe', '2f62705d8efaf004',
                '339940f502f9d32d', '7f803cbd7239c4f4', '9d48a534cbe4ec61', 'ac5c409f414d1b7a',
                'b1782cb0a4f6573a', 'b421473abc460e9e', 'ce89b94c58ebd4f4',
            ],
            'reason': (
                'at a flat maximum an error of 1e-3 L in the place changes the frequency by far '
                'less than 1e-4'
            ),
        },
        'a_peak_two_elements_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_peak_two_elements_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '1aa2304988e2d184', '240a972bfe6cf2dd', '39b75123e927c1c8', '41aabffa1814bec9',
                '4b729c5255e30cad', '4bcad220f4bb26d3', '5d1066af6330d9b6', '8161f2d120304bfd',
                '97cfce2535d230ed', '9e1fcf9bc66a485e', 'e6a0260115bd5e6f',
            ],
            'reason': (
                'the maximum is flat: a search on a 1e-3 L grid or a bounded optimiser find it '
                'within 1e-3 L (0.045 cm at most)'
            ),
        },
        'a_twin_cm': {
            'kind': 'abs', 'width': 0.05,
            'salt': 'ex04_peak/a_twin_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '141cbd81b9720cba', '2904a303644fd1f0', '2afa1efc0e9ea242', '4d586605e1e7943f',
                '67ff3408e2d52860', 'a15b6fdffd62cc6b', 'a850b85dcce9b63d', 'baa95013ef5d2553',
                'e279ea0cbaecd2c5', 'e356e0b258a5574f', 'e43f1b26775fb5af',
            ],
            'reason': (
                'any root-finder (or a 1e-3 L grid) on f(a) - f(twin_of L) beyond the maximum'
            ),
        },
    },
    'ex05_decay': {
        'tau_hand_ms': {
            'kind': 'rel', 'width': 0.04,
            'salt': 'ex05_decay/tau_hand_ms',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '42d854a228e4b807', '51f654831aac9e94', '5c83697ca6a052a8', '60548a77a60c8ba4',
                '893fa3def43b4bfb', '9bbd533a161cd191', 'aae563f3bb502aed', 'b56e25e3dc9473f9',
                'bb0da63f443e68bf', 'd7116e628bebaf27', 'f99019f6b98c8436',
            ],
            'reason': (
                'the window (ending 10 to 30 ms in, while the envelope is well above the noise) '
                'moves it by up to 4 %'
            ),
        },
        'tau_fit_ms': {
            'kind': 'rel', 'width': 0.002,
            'salt': 'ex05_decay/tau_fit_ms',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '213625337587a550', '64d9af9eb2c772ba', '75a5abb770d0e8a0', '9d82690d470f5cf5',
                '9e95339baacc909f', 'aba8aa1ef09cb5c6', 'd13f8509d42f681c', 'd8f5d16166b9dbca',
                'e3b12b2fc51fbbb4', 'f6164d48b3a6a2f0', 'fa30beba48e74166',
            ],
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by up to'
                ' 0.2 %'
            ),
        },
        'a_fit': {
            'kind': 'rel', 'width': 0.002,
            'salt': 'ex05_decay/a_fit',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2c07efa4cfb3869e', '5846b9859156bb47', '65362cce29c5e911', '76742b7896047da6',
                '8a2291b7f99d05ee', '8ba8257da49dbfd3', '8ed8ae94fac1d0df', '8efe0cf97d4c9016',
                'c9474da15226f386', 'df5b745cec89b20c', 'ecc40f69563ec4d7',
            ],
            'reason': (
                'fit_decay on these samples; a record cut to 500 to 800 samples moves it by up to'
                ' 0.2 %'
            ),
        },
    },
    'ex06_svm_dual': {
        'w1': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/w1',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2c303ca1248aecf3', '3a5b61d033832e34', '4c513d39b10eb552', '6fee1124db03073c',
                '7237aed61a9dab9e', '7ef4546edd0d0b6c', '9540bab4a4240c39', 'c531d49fdb89fe79',
                'c8e9681d2dacc474', 'e16e397640ede307', 'e3431c1c7432a304',
            ],
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'w2': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/w2',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0eca31d4e40caf82', '38619de6f9d313ce', '3ca40f2cf742fe78', '4d192a93b7d5c269',
                '80154be7aaf9670b', '8475456a1d8ce63a', '98490bc7df1728f2', 'a23d0d629ecc5f55',
                'e208975c273b2b24', 'f9cf80643b875fb9', 'fecdeabfcdcbb600',
            ],
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'b': {
            'kind': 'abs', 'width': 0.001,
            'salt': 'ex06_svm_dual/b',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '279720da6859e221', '32eee570470b539b', '4e4b67d34a3bfc5d', '664f5d0e6f41c0d9',
                '7b7c506a5eae6e83', '86a597c80ea1ffe5', 'a7c976d1685ffd06', 'b1bf1e0be837fa60',
                'b1e4d86554dfda40', 'c31fbd2fe519dd7f', 'dc0819ab13eb18f6',
            ],
            'reason': (
                'solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4'
            ),
        },
        'n_support': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex06_svm_dual/n_support',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2ed0a7f00c26264e',
            ],
            'reason': (
                'a count: multipliers above 1e-6'
            ),
        },
        'dual_objective': {
            'kind': 'abs', 'width': 0.0001,
            'salt': 'ex06_svm_dual/dual_objective',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '08b2fb8738721bac', '1ba2c91613d39889', '2982ccab8ad2d5b1', '337b3e4bd03534aa',
                '392fcaa24dbaf17a', '4881d9416c21b331', '4dcbef3173900bfc', '538d0d8654743ebb',
                '7df21d998b054c80', 'bb74e3bcdb108702', 'dfd929b887b81da3',
            ],
            'reason': (
                "a solver stopped at a duality gap g is within g of the optimum: SLSQP's below "
                "1e-5 (about 1e-14 here), SMO's n C tol = 3e-7 at tol=1e-8"
            ),
        },
    },
    'ex07_backprop': {
        'loss': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex07_backprop/loss',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '51919c60f77c8454', '7825941a8100177f', '972300027c24e5df', 'a5e2fee00fd12725',
                'b3a83bcbb8d72cc9', 'bb9350ba912a8f97', 'bf2ce301d229dd8f', 'c446ef65590aa0d3',
                'ea957dd55be5dc64', 'fe4e59306a1acb84', 'ffce520d50fe1c35',
            ],
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
        'loss_after_step': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex07_backprop/loss_after_step',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '02ddc5bb3bf6f57c', '04656b1da72fda9e', '144455509856de37', '4441336849d52ac4',
                '727196f00d750566', '83794e0d56d24f56', '89a986ce50617e83', 'a40f7fc5e4c3c4bf',
                'd608ec6be100be66', 'e1973113534c737f', 'e2878fd1dcadb95f',
            ],
            'reason': (
                'the same formula summed in another order changes only the last few of 16 digits'
            ),
        },
    },
    'ex08_filter_order': {
        'order': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex08_filter_order/order',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '9a865b27763123be',
            ],
            'reason': (
                "an integer: the next one above the formula's value"
            ),
        },
        'selectivity': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex08_filter_order/selectivity',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '06a3e5f93bf1f8e7', '48414dbb6199b034', '5d11bb66139b10d6', '7afac0a676b8e4d2',
                '7ce61edb19d518a9', '8644e3ce712173df', '8c578c1d3953f225', 'c81771f881fe84b5',
                'c8709054b37f6973', 'e1d4f31e27c0cac8', 'e2beb075b86544b2',
            ],
            'reason': (
                "the same closed formula; the edges' pre-warping is exact"
            ),
        },
        'radius_sos': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex08_filter_order/radius_sos',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '091fe3b3ecf646ef', '09f7c6040951d7b1', '32df3f88e326c24c', '478231f1b31c0542',
                '4c5379b3e00cb927', '74ec34d307897546', '7654cd2cf19d2a49', '7c6ae48bedaa2937',
                'ae630d3ebc8ea041', 'c868d35030756fd5', 'f6c6e16033dcf7bc',
            ],
            'reason': (
                'roots of quadratics from the same design, to rounding'
            ),
        },
        'n_coefficients_ba': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex08_filter_order/n_coefficients_ba',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                'd01ccc128319375a',
            ],
            'reason': (
                'a count of coefficients, which no rounding moves'
            ),
        },
    },
    'ex09_mesh_budget': {
        'n_predicted': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex09_mesh_budget/n_predicted',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '22f0ce60e0ae0102',
            ],
            'reason': (
                'a count: rounded up or to the nearest, from the observed order or exactly 4, it '
                'is the same count'
            ),
        },
        'n_needed': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex09_mesh_budget/n_needed',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                'e2db63a6d98c2058',
            ],
            'reason': (
                'a count: the smallest mesh that meets the budget'
            ),
        },
        'error_needed': {
            'kind': 'rel', 'width': 0.01,
            'salt': 'ex09_mesh_budget/error_needed',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '00477b7003b9e921', '0351d78020259938', '0dd947b911941c54', '0f1720822d2396b6',
                '531dfae9f27bf457', '5926a3a6eb9fcee5', '6472089135831f35', 'd8339805624fdf5b',
                'e66e79b61acc551c', 'efa5f7dd04571b8a', 'f913d31e0951019a',
            ],
            'reason': (
                'an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this'
                ' error of 1e-4 by far less than 1 %'
            ),
        },
    },
    'ex10_fifo': {
        'samples_after_50ms': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/samples_after_50ms',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '1a078ecfab2acbb9', '22ae1d466a12bc3c', '35d86ab0d8387d11', '8141f270776616e5',
                '87886694837aace7', '8c459d6e0cdc1a5f', 'b50a89dc266149c5', 'b807e32c9428dcc9',
                'ccb6d6551e2d9fe2', 'd5e4d2057c8a43a4', 'f8b0b441d9e8a359',
            ],
            'reason': (
                'one sample more or less, as the wait starts between two samples'
            ),
        },
        'arrived_while_reading': {
            'kind': 'abs', 'width': 2.0,
            'salt': 'ex10_fifo/arrived_while_reading',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0825126879dcc2a1', '3ea6573591567ab0', '47070502e56585b9', '6753df2dfd4c95ae',
                '73eb21b0ad66e236', 'a3ac1325c3d1a81d', 'a9bcdacbb66fa8d7', 'bb7a41cd63321b35',
                'c88d430f88d53116', 'ce963a26d87c4c8e', 'db0c4729df70f983',
            ],
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock move it by a '
                'sample or two'
            ),
        },
        'overflow_count': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex10_fifo/overflow_count',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '1ba9a3032785cf56',
            ],
            'reason': (
                'a count of bytes, which no rounding moves'
            ),
        },
        'lost': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/lost',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '154282c3f1ba6028', '2159f4fa0b6f19f7', '45a2c3cf9695b75b', '4c41390449baeede',
                '6027a665321c49bc', 'ba069102fee0dc03', 'c93fa495bdbd5948', 'e8bfc5cf4b9a2664',
                'ea1995baf12a2e85', 'efa74ee7c370025c', 'ff2b9d4e79e8be8c',
            ],
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock between the '
                "driver's calls move it by one sample"
            ),
        },
        'gap_ms': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex10_fifo/gap_ms',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '01a6ed19c03d98df', '11f3faf16aa0af8e', '3ccca0686263b86f', '3f860b39520ad99d',
                '44e152177900a26c', '45802937a653d101', '86c3f92ee03d3d6f', 'bb1cdd3203557b87',
                'bbd7e682a5c9a0af', 'd05bc326943d5711', 'f51febafdd0dfe2d',
            ],
            'reason': (
                'an extra register read or two (0.44 ms each) on the virtual clock between the '
                "driver's calls move it by under 1 ms"
            ),
        },
        'period_us': {
            'kind': 'rel', 'width': 1e-09,
            'salt': 'ex10_fifo/period_us',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '126bb8534d409857', '14371ffe21562a38', '2c1c6640f698c9a8', '43f45e638bfddaae',
                '5c5ced36ce78f211', '8f885d92fd807f89', '9259d4d0aa5c8e3c', '92e8b148ac8396e5',
                'aef645c5bc349a88', 'c2a14b96fe3b6876', 'd2169cf8f5488400',
            ],
            'reason': (
                'the middle of the bracket of a 5 % rate tolerance: rounding only'
            ),
        },
    },
    'ex11_rbf_cancellation': {
        'true': {
            'kind': 'rel', 'width': 1e-12,
            'salt': 'ex11_rbf_cancellation/true',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0573e61fc1a9c344', '3dacdbea5e9491fc', '4520986e833b03ce', '48a4facb95fcbf03',
                '578299e7418ca295', '8d051b2565e10fe7', 'a2e8175bd720f937', 'b06538bcd9ab9821',
                'b77d0407e53cd585', 'e08bd79e95dea32c', 'eec4d7732196bb77',
            ],
            'reason': (
                'a sum of five squares: only the last digits depend on the order'
            ),
        },
        'bound_1e6': {
            'kind': 'rel', 'width': 1e-06,
            'salt': 'ex11_rbf_cancellation/bound_1e6',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '15dce3ebbd57fc8c', '5cf8a38d3b6e4adb', '761968954f148bd3', '78b23a986924e5e3',
                '8fe36ca75c13b0bd', 'a4eb37edbcb9349a', 'ac751b7164d6849f', 'bca9b0e44176ec50',
                'ce9ae41846c7891a', 'd0183b0c8f4d4483', 'ec769698ac6732bc',
            ],
            'reason': (
                'the formula of the hint; norms summed in any order'
            ),
        },
        'error_1e6': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/error_1e6',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '12d3703f78b5e877', '16cd2e36c1d7d17e', '1ea4ef398dbf369c', '6db39de5bd3b64ce',
                '8f45fef78820b78d', '976dc166f31d06be', 'be9cfe8cdd79884f', 'c41aec21f011c6ed',
                'd7334fc55a0eb24b', 'eca42d56cfbf4677', 'f818d77d2f18bc29',
            ],
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'error_1e6_sums': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/error_1e6_sums',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '069fec0b7c78b4f2', '0a82049ac6339af5', '33fb94b3bccc6e5c', '3c03c4db8dc1f07e',
                '5286dbf4ae52552c', '5800cffa60c29bcd', '68487f0270b6447d', '738dd06a6e1fe010',
                'ccd485d266c11738', 'd7c5923bf7f71750', 'ebfbf7dd5ec43ed3',
            ],
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'direct_error_1e6': {
            'kind': 'factor', 'width': 10.0,
            'salt': 'ex11_rbf_cancellation/direct_error_1e6',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '121af88c6124fcc2', '3fa04e27263e1f74', '4851ff9aedce4127', '7dc3a6a7e0a6e432',
                '8e16a2ca5d173f46', '9dfdd93cc8282768', 'a7d76de217e9495a', 'c4d9f2252fb70abb',
                'c73859b86f2db496', 'dda2e85bbdd603b4', 'ecca66cbca9c4160',
            ],
            'reason': (
                'rounding errors depend on the order of the operations: sums in another order '
                'differ by a factor of up to 6'
            ),
        },
        'libsvm_drift_1e6': {
            'kind': 'factor', 'width': 3.0,
            'salt': 'ex11_rbf_cancellation/libsvm_drift_1e6',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2642d9232aa5794a', '319b359791b0398b', '5ff9a912355bc87a', '6ea8626e82ab6e9d',
                '824c3d1338fb452c', '8c0b4594abe393a9', 'a119578baad60d49', 'b2bf59d15178b0fc',
                'ddca25f4dc969710', 'e68e1c4bda5d1645', 'fddb264cf605f325',
            ],
            'reason': (
                'scikit-learn versions and BLAS libraries round the training kernel differently'
            ),
        },
    },
    'ex12_splits': {
        'chance': {
            'kind': 'abs', 'width': 0.005,
            'salt': 'ex12_splits/chance',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '5f3b0cee7bdc4d78', '735bad08ec351174', '77b48515f6c58a8e', '78462d3978d47772',
                '79c04f14d4f0f0ca', '910bc7d78327f93e', 'b7a1f1c6c20341f4', 'dff62c01b14cc020',
                'f3eb7acb1be80178', 'faa3f71610ddd455', 'fb5be6fd984dcfe8',
            ],
            'reason': (
                'one over the number of materials, rounded to two digits'
            ),
        },
        'seen_random': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex12_splits/seen_random',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                'f4f931af06504909',
            ],
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'seen_grouped': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex12_splits/seen_grouped',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2fc904d22e515b16',
            ],
            'reason': (
                'a share of whole recordings, from the seeded split'
            ),
        },
        'accuracy_random': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_random',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '01403a6996518323', '05782edf0aa55705', '1886514239e0318f', '2cdcdc4704fabba7',
                '36be801a13302695', '3a8138cc93a327f2', '613a0a1c8e563548', '636aa45376344fab',
                '6574b0c92d27beea', '8ad89619ce0e8e57', 'ab1db33e96a59f04',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_grouped': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_grouped',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2017e010209d5fc5', '2c4eb536cdf6df87', '7a3ff5a5fbded31a', '8229a8cdad25aaaa',
                '861b962d4f5338ec', '869b489363837e5b', '8c4c051fd5df8aa6', '8e7d22c33a2fb65a',
                '9ad1a121beb20893', 'a8a17e1bc57da9f5', 'fafbede3df7ad98e',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
        'accuracy_rigid': {
            'kind': 'abs', 'width': 0.035,
            'salt': 'ex12_splits/accuracy_rigid',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '00d57f465aa4f132', '22992ae2dd0b834c', '3202c6ae3b05dc7c', '3a0d1c6310c3607d',
                '53838f5cb1389d08', '726e4a8e036c38d8', '8faf60fce6233c6f', '924331d4578b7243',
                'b63bb27e941a7760', 'e4a0362d1f386653', 'f5912d02489d7ffd',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip one test recording of'
                ' 30'
            ),
        },
    },
    'ex13_mode_curves': {
        'spread_f1_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/spread_f1_pct',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '17397fe7f26aac44', '2de372236452c56b', '3b4986962d67302a', '519a945cb5c74599',
                '9e09df62cd356f0d', 'a6340cab162c6563', 'abb12d4eec2fd852', 'de97187185fa805e',
                'e1876431885c77d3', 'f3ed9066b01ebf2e', 'f58d6945ab5cedb5',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'spread_f2_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/spread_f2_pct',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '03f1027b32fffaff', '15014dd2ea3de145', '25ced3b2f6c8626f', '4088ed43b6289b57',
                '5468fbc4d635bea0', '5d5fb7158d080621', '7098a9380b5412bf', 'ac27b78444c43853',
                'ba6d01bb5b6b750e', 'e2c82a0e3aee19fb', 'f96d93f729864fb6',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'repeat_pct': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/repeat_pct',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '197af4e5ac36797d', '2fe38ee55ec1ff6e', '306dbd90e77c300c', '3716dde9c4681263',
                '43653a36c3d1e703', '49b799b784b03378', '5c6e9a915b16a08f', '71fd9d68702da004',
                'a7a1ea41b732a9f3', 'aa1f8367eb26711a', 'ba091df119971db4',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'curve_accuracy': {
            'kind': 'abs', 'width': 0.03,
            'salt': 'ex13_mode_curves/curve_accuracy',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '04c742216093975c', '1f6067c05ea68992', '36a574e97b56abd8', '43c719b3391aefeb',
                '49dc6aa896a957af', '4a39d6380d614bb7', '4fb6b0a2582aaec7', 'a01b988d66948e40',
                'df452243af1b9323', 'f8a1cb43226f3a61', 'ff73d5b184266720',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' the held-out set'
            ),
        },
        'n_correct': {
            'kind': 'abs', 'width': 2.0,
            'salt': 'ex13_mode_curves/n_correct',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '025b0f5856bae0b7', '2def95a650f8704f', '3f41b7f0143aab97', '440afb450dca00d2',
                '59f530846e9e0a11', '87fc8725d9da0864', 'a88911771df5dc15', 'c0831809cf4ddf86',
                'cf2b6f421ab38ff5', 'f05a29ebe45d910d', 'f6805d700d77a100',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' the held-out set'
            ),
        },
        'n_test': {
            'kind': 'abs', 'width': 0.0,
            'salt': 'ex13_mode_curves/n_test',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                'f38e1e3376fbe88e',
            ],
            'reason': (
                'the held-out recordings of the seeded grouped split'
            ),
        },
        'distance_cm': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/distance_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '13817f980c4362c1', '321ce1d43d290404', '5de4a77cbf2d001f', '897cbc2bc89ce809',
                'a5c9953576519917', 'c9004676b99d42e9', 'cbfabb1542792017', 'e02b0d799d532fdb',
                'e6d4c4c1a9dcf4f4', 'f6d80a8ce53019b9', 'fc4f2558a9a110f2',
            ],
            'reason': (
                'peak_frequencies interpolates between FFT bins: another interpolation moves a '
                'peak by a small part of a bin'
            ),
        },
        'svm_accuracy': {
            'kind': 'abs', 'width': 0.03,
            'salt': 'ex13_mode_curves/svm_accuracy',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '17d5dc8a28c3ee97', '28fe8e9088f60da0', '305bc7086dbe0e7a', '34afa799051a5e48',
                '457967d8ebf29105', '4bf4ae5275bb2d73', '5f2a2a4fb6c3d66d', '76a202ccceba0538',
                'b09af47528711a6c', 'baa65dcfee0fed3f', 'edc559edf1870873',
            ],
            'reason': (
                'the same data and split; another solver tolerance may flip a recording or two of'
                ' the held-out set'
            ),
        },
        'bins_per_cm': {
            'kind': 'rel', 'width': 0.1,
            'salt': 'ex13_mode_curves/bins_per_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '228b5d1cf97387c3', '2673e3a3de9259fa', '53d6ee1f6c658194', '591bafee652bbfbd',
                '60810ad8546068c0', '6c939939697e1f33', 'af4bc65bc9cc442d', 'af8363c6798fd0dd',
                'cbed0c72eb62a306', 'd0e2f1f4e3de69bc', 'ed263cc11e49f57e',
            ],
            'reason': (
                'a jump threshold of 5 to 20 bins, or another peak interpolation, moves the '
                'median by a few per cent'
            ),
        },
        'metals_smooth_from_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/metals_smooth_from_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '05f01eabfc2c2b1b', '06f178b11ec452eb', '1128f82d9fb30ab3', '1861fbe002e79c45',
                '4200ca104132a127', '6018fcd5d3d6edc4', '9c6315cbc780242e', 'aad98a889e9f3d56',
                'c174179f30deefd8', 'c8c928b3151b81ce', 'e1d2b63bab72d3fd',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'metals_smooth_to_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/metals_smooth_to_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0de59577a2a40b40', '0fc67404b512171c', '2b8fa3208a31cef3', '2c42d9d80bba8f5e',
                '33b36568509b278a', '50edbca3372bea9a', '8c0dfd81db1d9ee3', '8d112d6c3c98764c',
                'a7703c81dfd44b1e', 'be9863f545ec8b0a', 'e8834b0c6075491d',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_from_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/pvc_smooth_from_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '130bd0d1866d3100', '409c6f90a765bd7c', '89a046c3d3d3aae8', '91667af6599c0f84',
                'b0ac40a057e44327', 'bb10db5497c923e5', 'dcde86365d27d353', 'e5940907e97b8624',
                'ea93dbf3bfc40b97', 'f75b539b0b924670', 'ff20f0e8b62b0d80',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'pvc_smooth_to_cm': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/pvc_smooth_to_cm',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '1ce553e2c9205895', '23aa3280e8cb255c', '2d48b5e04de0b6a8', '3067719952f1632e',
                '4ff57143c6824e8a', '769b69460be6c52a', '994d82840401333d', 'ab68c8a1d0977c12',
                'ae9d6e95c33a9581', 'c000f21b5bfbef79', 'e303a10208863fd0',
            ],
            'reason': (
                'one 1 cm step: a jump threshold other than 10 bins may move an end by a position'
            ),
        },
        'restrikes_median': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/restrikes_median',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0283be96d2624193', '19a140b15b899511', '1a768e2f86abe68d', '3eedcd4a922f14c0',
                '5bdaaf4595267c02', '640f7c3afec6ada6', '64731637b0954d00', '69dacdf8ddd6e552',
                'd029b6fe5b6f84a8', 'f16e7cbcb391cddc', 'f60fbc065feb7a57',
            ],
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
        'restrikes_max': {
            'kind': 'abs', 'width': 1.0,
            'salt': 'ex13_mode_curves/restrikes_max',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0b8b5d7a0e40cb8e', '6504fb4ee91358b4', '72082dff3f737093', '775b96286629fe35',
                '7ad68325d0718ed6', '8aed7fe6cdac5b94', 'a9468b3b1bc9874f', 'c905618b434cfa33',
                'df684b4e28333aa4', 'e716f800d523fb89', 'f0c6b53d71d79ff3',
            ],
            'reason': (
                'read from the data set; a last-bit difference of the simulation may move a count'
                ' by one'
            ),
        },
    },
    'ex14_kalman': {
        'k_steady': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex14_kalman/k_steady',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0c734ae4cced3c50', '3b5040a6c1394811', '4c2b8579e5211d49', '5aa5ee77a4b3b848',
                '5fd204dd106718fb', '7dce1b7866a9b7ea', '87f39accdab6ff9c', '928db7bd51a3556f',
                'c6a54d1a95083b1c', 'e1cd332c6424d5a6', 'eb3e444cbbaec1fd',
            ],
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'sigma_steady': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex14_kalman/sigma_steady',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0097e48507523b7e', '2410ca4a00d927b8', '2467a7eab6007bf9', '2a335bf39535e4ef',
                '3906809b5497319e', '3c7868845766d6f1', '6282825561157d71', '896f6b3b91ee1f4d',
                'a4711bac9dcfdfc3', 'af4fb20a38b6d030', 'e704419e6adb31d3',
            ],
            'reason': (
                'a closed form: any right algebra gives it to rounding, or to five copied digits'
            ),
        },
        'rms_raw': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_raw',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0625b54a308d1b71', '5a0dd4bd9e4bf5ce', '5f20f02a7dbe7cda', '60b1711f0681fa84',
                '627e323495397dd4', '6acd358fa5a07de6', '71b1ca15ef5f7962', '88fbc5361cd39e31',
                'aa83c344d2a0f921', 'beef34041d68090e', 'ce0eb9dada8e5c61',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_filtered': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_filtered',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0e2d24a4fecdbaf6', '47df0fa6f0a8afa8', '57c3812237cba17f', '6610a63aa53d3cae',
                '7bb78d8c121f243b', '968d960da26b3ee9', '9d82104d08aca4bd', '9ebd1d0940d3cf82',
                'c9a4c73b06dfc719', 'dd52b502c45591a1', 'ebb838aa6e38913e',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_small': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_q_small',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '05708bca1203c646', '0ddf2e1e55dc9d1f', '7ce6f9dedb32512a', 'a8f96b3b79c8c21d',
                'ac0ef3f2ecb03e4d', 'b74da9e2a47f4b2d', 'd579042d82493add', 'd8b7c2f883b29713',
                'e23e34e1372dcf22', 'f2319b66dec98126', 'fbb9c03ab53f5bad',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
        'rms_q_large': {
            'kind': 'rel', 'width': 0.001,
            'salt': 'ex14_kalman/rms_q_large',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '33b92e94255cb8c0', '4227757216904647', '449d5bf9e2be3b5e', '817668489bcb206e',
                '94934bab935c994a', '94c44ff2025e8ac3', '94d16b074c6b35ee', 'b45e7950c3cd0419',
                'c1a5b25ca62f78f1', 'e5653e66fca022d4', 'ecfa96274c3dea92',
            ],
            'reason': (
                'the statement fixes the data, the filter and the cut at 1000 samples: only sums '
                'differ'
            ),
        },
    },
    'ex15_design_effect': {
        'accuracy': {
            'kind': 'abs', 'width': 0.0025,
            'salt': 'ex15_design_effect/accuracy',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '2c881f312d02d268', '410e66d3f41bb196', '59f685dcb735f430', '6be673f575edddb7',
                '763820cad46545d4', '9786115e4ab0fb1c', 'a82fd52410167c47', 'b004f0518a5a5c06',
                'e37bdc116e61f616', 'f52b8554dc0c3023', 'fc1d954d5b0a47a7',
            ],
            'reason': (
                'a count of right answers out of 200: half of one in 200'
            ),
        },
        'rec_low': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/rec_low',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '03321702550ba94b', '26efc51c206752c5', '56cc14aa133cc53d', '591a5ae0644bc0cb',
                '5a2c99258477466a', '5a3cd32cd3c92875', '73b1e3b9b21e36aa', 'b7a77f750710105b',
                'bea542faef31f91e', 'bfcddf2dd227b826', 'fc0bc2006058f044',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'rec_high': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/rec_high',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '03890a8336782c08', '27e7288975d2d2c3', '31405faefd587070', '428a93b596b9ffbb',
                '75bfcf8e00576f3d', '94e626991cad047a', '9ab8290689d9b3ed', 'a47560cc714c7a83',
                'b690deb6ae246cdd', 'c06cdf7892e69efe', 'f58acb9a8cf6a2f5',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'icc': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/icc',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '12853652c07eec2a', '1c34841d40d45201', '36c13b86a680002b', '95f2edba6074db7f',
                'b122a086d8343654', 'c681749952f08e9d', 'd659e2133364fcd8', 'd845bd52c76261b2',
                'e35564293228b214', 'e5d994eeae044211', 'f688881cf0553037',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'deff_icc': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/deff_icc',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '1b611eb06ec9ad9b', '25ad2819d1e48ba9', '49c8833e99fe665d', '540df2a9b4489e77',
                '55429607cd19fe97', '796309d45ebbc32c', '98509dc3e3282046', 'b3c0682d8085b648',
                'db2be55c42e72cf5', 'f3bc1ba0cc5db809', 'f9abe31782947b40',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'deff': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/deff',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '10144a7bfc1d7f3a', '17ea3a91d95bb92f', '45127f88de45e7c8', '454590d67ded439f',
                '66c332a125594268', '749635e57c5bb193', '883f3353611b9b9f', '8c2b96091f762195',
                'cd1792090d1809da', 'd4e4efe29869d20c', 'e72252ca4bffc92f',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'n_eff': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/n_eff',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '100690cc4cd6a656', '3ce9c10f453be8f2', '3e93e74d749bc865', '7094730df499cd0c',
                '996bc155de736972', 'b5e87d8d72725ee1', 'ceac125cbe9ff040', 'd18ed69fb7872a94',
                'e3195e442ad5ce7b', 'f1adcbdfe93661a2', 'f8903ee9b4d1dd0a',
            ],
            'reason': (
                'sums of squares of whole counts: rounding only, or five copied digits'
            ),
        },
        'eff_low': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/eff_low',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '5ccb967439157621', '80dfefbf6be0363d', '93dce3a5cd265bb7', 'a1e2740ff8a5bec9',
                'a5dd18f4517ddec6', 'a9ced5dbc83b6122', 'b0fc35515ee09355', 'b2d47c87b0f60aa4',
                'cd28452e376fdb7a', 'da23d4327b36c498', 'db915ba6b56af0cd',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'eff_high': {
            'kind': 'rel', 'width': 0.0001,
            'salt': 'ex15_design_effect/eff_high',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '129732ac14695e37', '1f69c3024609b14e', '1f7398de054c0f95', '3ec151ae1a6851ca',
                '5307bf03e474179b', '6857a0bba2c59b39', '7e091777c6f318c7', '93516bcfc249ff2c',
                '9b998cbf92cb1f0b', 'beca1a4a8153078e', 'd7d6b72c6a1cfcba',
            ],
            'reason': (
                'a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied'
                ' digits'
            ),
        },
        'boot_low': {
            'kind': 'abs', 'width': 0.0125,
            'salt': 'ex15_design_effect/boot_low',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0b973cafc99943ac', '1a6ba021587ed24d', '1c1e7724309350cc', '27c8ee1cb44bec1d',
                '78a5b3d082f82cbd', '7d70f62a73b40675', '91b99d77d941f931', 'd6e70b251e6cad06',
                'd7992f00943a3a08', 'dca6325c70b9dbf2', 'e58ab6cf7bfca863',
            ],
            'reason': (
                "another seed's 10000 resamples move an end by at most 2 steps of 1/200 (4 sd of "
                'a percentile), half a step for quantile conventions'
            ),
        },
        'boot_high': {
            'kind': 'abs', 'width': 0.0125,
            'salt': 'ex15_design_effect/boot_high',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '140775dc3afa0c39', '20e6c07f8db17f20', '2c5ccdb55f4818f0', '40f462206193d22d',
                '612034d1ca15e60f', '61d75bd7cf09a23d', '90983677ce813bd0', 'b9e971caee8dd9bd',
                'cc445b5f4c3ac12a', 'e550488a1fe840a2', 'e87cd2e7e496f53b',
            ],
            'reason': (
                "another seed's 10000 resamples move an end by at most 2 steps of 1/200 (4 sd of "
                'a percentile), half a step for quantile conventions'
            ),
        },
        'coverage_recording': {
            'kind': 'abs', 'width': 0.0005,
            'salt': 'ex15_design_effect/coverage_recording',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0da3c95bdaa895c0', '361b38c3db70e4bc', '4f91e528ccb4f542', '6ddea0584f4ed6f3',
                '712005b2db2f7b8a', '80f6554a5c0abb67', '9903aae66cc168d7', 'a30997159b9f79f7',
                'a483b8190fded741', 'a4921f93401a8cda', 'ddc78dc1dcacd125',
            ],
            'reason': (
                "a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding "
                'or z = 1.96 flips none; half a design'
            ),
        },
        'coverage_deff': {
            'kind': 'abs', 'width': 0.0005,
            'salt': 'ex15_design_effect/coverage_deff',
            'kdf': {'name': 'scrypt', 'n': 16384, 'r': 8, 'p': 1},
            'cells': [
                '0956b970fb2a043c', '24023544bd2d95a7', '3ea42e2cc31705ca', '67161d548fbd5fa7',
                '8c7ba8405e7ed604', '9b36221adc0dacd8', 'b2dd86ecfaac6b97', 'b83607864ed1a19b',
                'cfa0ab2f8da93cc5', 'da83c36add623c67', 'fe3e64e54860fbae',
            ],
            'reason': (
                "a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding "
                'or z = 1.96 flips none; half a design'
            ),
        },
    },
}
